// The heap's shape in its front-view picture (measure/heap_profile.h): run-out, height and the
// profile's convexity, on ridges of known profile. A ridge of small spheres (r = 1 mm on a 100 mm
// heap) whose centres follow z(x) shows the profile offset by r: its convexity differs from the
// curve's by O(r / L) = 1 %, hence the 0.02 tolerance; the run-out is exact to a pixel.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "measure/bed_height.h"
#include "measure/heap_angle.h"
#include "measure/heap_profile.h"

using namespace repose;

namespace {

// A ridge along y whose both faces follow height(|x|) for |x| <= half_width, sphere centres every
// r / 2 along x, five rows along y.
std::vector<Sphere> ridge(const std::function<double(double)>& height, double half_width, double r) {
  std::vector<Sphere> spheres;
  for (int iy = -2; iy <= 2; ++iy)
    for (double x = -half_width; x <= half_width + 1e-12; x += 0.5 * r)
      spheres.push_back({{x, 0.01 * iy, height(std::abs(x))}, r});
  return spheres;
}

HeapProfile profile_of(const std::vector<Sphere>& spheres) {
  HeapAngleOptions options;
  options.floor_z = -0.001;  // the sphere centres at z = 0 rest on it
  return measure_heap_profile(measure_heap_angle(spheres, options));
}

}  // namespace

TEST_CASE("profile convexity: a dome bulges, a sagging slope sags, a straight one neither", "[heap]") {
  // The fit sees the profile between 2 % and 98 % of the height (H + 2 r above the floor, r below
  // the centres). For the dome z = H (1 - (x/L)^2) that is x in [0.143 L, L]: span 0.857 L, slope at
  // its middle -1.143 H / L, curvature -2 H / L^2, so the convexity -c span / (4 |b|) is +0.1875.
  // The sag z = H (1 - x/L)^2 spans x in [0.010 L, 0.980 L]: slope -1.010 H / L at its middle,
  // curvature +2 H / L^2: -0.240. A straight face: 0.
  const double H = 0.1, L = 0.2, r = 0.001;
  struct Case {
    const char* name;
    std::function<double(double)> z;
    double expected;
  };
  for (const Case& c : {Case{"dome", [&](double x) { return H * (1 - (x / L) * (x / L)); }, 0.1875},
                        Case{"sag", [&](double x) { return H * (1 - x / L) * (1 - x / L); }, -0.240},
                        Case{"straight", [&](double x) { return H * (1 - x / L); }, 0.0}}) {
    HeapProfile p = profile_of(ridge(c.z, L, r));
    INFO(c.name << ": left " << p.left.convexity << ", right " << p.right.convexity);
    REQUIRE(p.left.valid);
    REQUIRE(p.right.valid);
    CHECK(p.right.convexity == Approx(c.expected).margin(0.02));
    CHECK(p.left.convexity == Approx(c.expected).margin(0.02));
    CHECK(p.height == Approx(H + 2 * r).margin(1e-3 * L));  // the floor lies r below the centres
  }
}

TEST_CASE("run-out reaches the toe of the heap, not a grain beyond a gap", "[heap]") {
  const double H = 0.1, L = 0.2, r = 0.001;
  std::vector<Sphere> heap = ridge([&](double x) { return H * (1 - x / L); }, L, r);
  HeapProfile p = profile_of(heap);
  // The crest column lies within a pixel of x = 0; the toe is the last sphere's far edge.
  double pixel = (2 * L + 2 * r) / 1600;
  CHECK(p.right.runout == Approx(L + r).margin(2 * pixel));
  CHECK(p.left.runout == Approx(L + r).margin(2 * pixel));
  CHECK(p.right.toe == Approx(L + r).margin(2 * pixel));
  heap.push_back({{L + 0.05, 0.0, 0.0}, r});  // rolled away: 50 mm beyond the toe
  HeapProfile q = profile_of(heap);
  CHECK(q.right.runout == Approx(L + r).margin(4 * pixel));  // a coarser picture (wider extent)
}

TEST_CASE("a side without a slope is reported, not fitted", "[heap]") {
  // A heap standing against x = 0 (crest at the back): nothing to its left.
  const double H = 0.1, L = 0.2, r = 0.001;
  std::vector<Sphere> half;
  for (double x = 0; x <= L; x += 0.5 * r) half.push_back({{x, 0.0, H * (1 - x / L)}, r});
  HeapProfile p = profile_of(half);
  CHECK_FALSE(p.left.valid);
  CHECK_FALSE(p.left.problem.empty());
  CHECK(p.right.valid);
  CHECK(p.right.convexity == Approx(0).margin(0.02));
}

TEST_CASE("bed height: a uniform bed's own height, whatever its grains", "[heap]") {
  // A cubic lattice of spheres touching the floor fills 0 .. 2 r n: twice the mean centre height.
  std::vector<Sphere> bed;
  const double r = 0.005;
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) bed.push_back({{2 * r * i, 0.0, r + 2 * r * k}, r});
  CHECK(uniform_bed_height(bed) == Approx(8 * r));
  CHECK(uniform_bed_height(bed, -0.01) == Approx(8 * r + 0.02));
  CHECK(uniform_bed_height({}) == 0.0);
}
