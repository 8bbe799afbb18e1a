// The shipped clump templates: counts and hulls as the seeds state them, and the CSV files in
// cases/templates/ in step with their generators.
#include <catch2/catch.hpp>

#include <cmath>
#include <glm/geometric.hpp>

#include "geometry/clump.h"
#include "geometry/sphere_csv.h"
#include "geometry/templates.h"
#include "util/math.h"

using namespace repose;

namespace {

struct Hull {
  glm::dvec3 lower{HUGE_VAL}, upper{-HUGE_VAL};
  double radial = 0;  // largest distance of the surface from the z axis
};
Hull hull(const ClumpTemplate& t) {
  Hull h;
  for (const Sphere& s : t.spheres) {
    h.lower = glm::min(h.lower, s.centre - s.radius);
    h.upper = glm::max(h.upper, s.centre + s.radius);
    h.radial = std::max(h.radial, std::hypot(s.centre.x, s.centre.y) + s.radius);
  }
  return h;
}

}  // namespace

TEST_CASE("cotton stalk: 40 layers x 18 spheres of 1 mm, 10 mm x 80 mm", "[templates]") {
  const ClumpTemplate stalk = cotton_stalk();
  REQUIRE(stalk.spheres.size() == 720);
  for (const Sphere& s : stalk.spheres) CHECK(s.radius == 1e-3);
  const Hull h = hull(stalk);
  CHECK(h.radial == Approx(5e-3).epsilon(1e-12));
  CHECK(h.upper.z - h.lower.z == Approx(80e-3).epsilon(1e-12));
  // Layer k+1 is layer k turned by 30 degrees about the axis.
  for (int k = 0; k < 18; ++k) {
    const glm::dvec3 a = stalk.spheres[k].centre, b = stalk.spheres[18 + k].centre;
    const double turn = std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y);
    CHECK(turn == Approx(30.0 * repose::kPi / 180.0).epsilon(1e-12));
    CHECK(b.z - a.z == Approx(2e-3).epsilon(1e-12));
  }
}

TEST_CASE("coarse stalk keeps the hull with 48 spheres", "[templates]") {
  const ClumpTemplate coarse = make_shipped_template("cotton_stalk_coarse");
  CHECK(coarse.spheres.size() == 48);
  const Hull h = hull(coarse);
  CHECK(h.radial == Approx(5e-3).epsilon(1e-12));
  CHECK(h.upper.z - h.lower.z == Approx(80e-3).epsilon(1e-12));
}

TEST_CASE("cabbage: 160 mm core and 202 vein and stem spheres", "[templates]") {
  const ClumpTemplate head = cabbage();
  REQUIRE(head.spheres.size() == 203);
  CHECK(head.spheres[0].radius == 0.080);
  CHECK(head.spheres[0].centre == glm::dvec3(0.0));
  for (size_t i = 1; i < head.spheres.size(); ++i) {
    const Sphere& s = head.spheres[i];
    const double protrusion = glm::length(s.centre) + s.radius - 0.080;
    CHECK(s.radius >= 5e-3 - 1e-15);
    CHECK(s.radius <= 15e-3 + 1e-15);
    CHECK(protrusion >= 2e-3 - 1e-12);
    CHECK(protrusion <= 6e-3 + 1e-12);
  }
  // The stem is the -z pole: nothing reaches further down.
  const Hull h = hull(head);
  CHECK(h.lower.z == Approx(-0.086).epsilon(1e-12));
}

TEST_CASE("sliding-test groups: four cabbages in a 2x2 square, two stalks side by side", "[templates]") {
  const ClumpTemplate head = cabbage();
  const ClumpTemplate group = cabbage_group4(head);
  REQUIRE(group.spheres.size() == 4 * 203);
  // Cores at the corners of a square whose side makes facing veins touch.
  const double reach = hull(head).upper.x;
  for (int k = 0; k < 4; ++k) {
    const glm::dvec3 core = group.spheres[static_cast<size_t>(k) * 203].centre;
    CHECK(std::abs(core.x) == Approx(reach).epsilon(1e-12));
    CHECK(std::abs(core.y) == Approx(reach).epsilon(1e-12));
  }
  const ClumpTemplate pair = cotton_stalk_group2(cotton_stalk());
  REQUIRE(pair.spheres.size() == 1440);
  const Hull h = hull(pair);
  CHECK(h.upper.x - h.lower.x == Approx(20e-3).epsilon(1e-12));
}

TEST_CASE("cases/templates CSV files match their generators", "[templates]") {
  for (const ShippedTemplate& t : shipped_templates()) {
    INFO(t.name);
    const std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/templates/" + t.name + ".csv";
    const std::vector<Sphere> file = read_sphere_csv(path);
    const ClumpTemplate generated = t.make();
    REQUIRE(file.size() == generated.spheres.size());
    for (size_t i = 0; i < file.size(); ++i) {
      CHECK(file[i].centre == generated.spheres[i].centre);
      CHECK(file[i].radius == generated.spheres[i].radius);
    }
  }
}

TEST_CASE("unknown template names list the known ones", "[templates]") {
  CHECK_THROWS_WITH(make_shipped_template("lettuce"), Catch::Contains("known: cabbage, cabbage_group4"));
}
