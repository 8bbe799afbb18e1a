// Fills and lattices: deterministic to the byte, overlap-free, inside their regions, exact counts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "case/case_error.h"
#include "case/case_loader.h"
#include "case/particle_factory.h"
#include "geometry/sphere_grid.h"

using namespace repose;

namespace {

FillSpec box_fill(int count, double radius_min, double radius_max, uint64_t seed) {
  FillSpec fill;
  fill.shape = FillSpec::Shape::Box;
  fill.box_min = {0, 0, 0};
  fill.box_max = {0.1, 0.1, 0.2};
  fill.count = count;
  fill.radius_min = radius_min;
  fill.radius_max = radius_max;
  fill.seed = seed;
  fill.where = {"t.toml", "fill[0]", 3};
  return fill;
}

// Brute force: every pair, no grid, so it checks SphereGrid as well.
bool any_overlap(const std::vector<SphereSpec>& spheres) {
  for (size_t i = 0; i < spheres.size(); ++i)
    for (size_t j = 0; j < i; ++j) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(spheres[i].position[a] - spheres[j].position[a], 2);
      double reach = spheres[i].radius + spheres[j].radius;
      if (d2 < reach * reach) return true;
    }
  return false;
}

bool same_bytes(const std::vector<SphereSpec>& a, const std::vector<SphereSpec>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(a[i].position.data(), b[i].position.data(), sizeof(Vec3d)) != 0 ||
        std::memcmp(&a[i].radius, &b[i].radius, sizeof(double)) != 0)
      return false;
  return true;
}

}  // namespace

TEST_CASE("raw draws map to the unit interval without the standard library's distributions") {
  CHECK(unit_interval(0) == 0.0);
  CHECK(unit_interval(~0ull) == 1.0 - 0x1.0p-53);
  CHECK(unit_interval(1ull << 63) == 0.5);
  // std::mt19937_64 itself is fixed by the standard: its 10000th draw from the default seed.
  std::mt19937_64 engine;
  engine.discard(9999);
  CHECK(engine() == 9981545732273789042ull);
}

TEST_CASE("a fill is the same to the byte for the same seed, and differs for another") {
  std::vector<SphereSpec> first, second, other;
  append_fill(box_fill(800, 0.004, 0.006, 42), first);
  append_fill(box_fill(800, 0.004, 0.006, 42), second);
  append_fill(box_fill(800, 0.004, 0.006, 43), other);
  CHECK(same_bytes(first, second));
  CHECK(!same_bytes(first, other));
  // Pinned: the first sphere of seed 42, so a change of the mapping is noticed.
  std::mt19937_64 engine(42);
  double radius = 0.004 + 0.002 * unit_interval(engine());
  double x = radius + (0.1 - 2 * radius) * unit_interval(engine());
  CHECK(first[0].radius == radius);
  CHECK(first[0].position[0] == x);
}

TEST_CASE("box fills are overlap-free, inside with a radius margin, sizes within range") {
  std::vector<SphereSpec> spheres;
  FillSpec fill = box_fill(800, 0.004, 0.006, 7);
  fill.velocity = {0, 0, -1};
  fill.material = 2;
  append_fill(fill, spheres);
  REQUIRE(spheres.size() == 800);
  CHECK(!any_overlap(spheres));
  for (const SphereSpec& s : spheres) {
    CHECK(s.radius >= 0.004);
    CHECK(s.radius <= 0.006);
    for (int a = 0; a < 3; ++a) {
      CHECK(s.position[a] - s.radius >= fill.box_min[a]);
      CHECK(s.position[a] + s.radius <= fill.box_max[a]);
    }
    CHECK(s.velocity == Vec3d{0, 0, -1});
    CHECK(s.material == 2);
    CHECK(s.where.key == "fill[0]");
  }
}

TEST_CASE("cylinder fills stay inside a tilted cylinder") {
  FillSpec fill;
  fill.shape = FillSpec::Shape::Cylinder;
  fill.cyl_base = {0.1, -0.2, 0.3};
  double n = std::sqrt(2.0);
  fill.cyl_axis = {1 / n, 0, 1 / n};
  fill.cyl_radius = 0.05;
  fill.cyl_height = 0.2;
  fill.count = 1000;
  fill.radius_min = fill.radius_max = 0.004;
  fill.seed = 3;
  std::vector<SphereSpec> spheres;
  append_fill(fill, spheres);
  CHECK(!any_overlap(spheres));
  for (const SphereSpec& s : spheres) {
    Vec3d d{s.position[0] - fill.cyl_base[0], s.position[1] - fill.cyl_base[1], s.position[2] - fill.cyl_base[2]};
    double along = d[0] * fill.cyl_axis[0] + d[1] * fill.cyl_axis[1] + d[2] * fill.cyl_axis[2];
    double off2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - along * along;
    CHECK(along >= s.radius - 1e-12);
    CHECK(along <= fill.cyl_height - s.radius + 1e-12);
    CHECK(std::sqrt(std::max(0.0, off2)) <= fill.cyl_radius - s.radius + 1e-12);
  }
}

TEST_CASE("fills avoid spheres placed before them, big or small") {
  std::vector<SphereSpec> spheres(2);
  spheres[0].position = {0.05, 0.05, 0.1};
  spheres[0].radius = 0.04;  // a large explicit sphere in the middle of the region
  spheres[1].position = {0.02, 0.02, 0.02};
  spheres[1].radius = 0.003;
  append_fill(box_fill(600, 0.003, 0.003, 5), spheres);
  CHECK(spheres.size() == 602);
  CHECK(!any_overlap(spheres));
}

TEST_CASE("explicit overlap check names both spheres") {
  std::vector<SphereSpec> spheres(3);
  for (int i = 0; i < 3; ++i) {
    spheres[size_t(i)].radius = 0.01;
    spheres[size_t(i)].position = {0.03 * i, 0, 0};
    spheres[size_t(i)].where = {"s.toml", "sphere[" + std::to_string(i) + "]", 10 + 5 * i};
  }
  CHECK_NOTHROW(check_no_overlaps(spheres));
  spheres[2].position = {0.045, 0.001, 0};
  CHECK_THROWS_WITH(check_no_overlaps(spheres), Catch::Matchers::StartsWith("s.toml:20: sphere[2]: overlaps sphere[1] (line 15)"));
}

TEST_CASE("lattice counts are exact for a known box") {
  LatticeSpec lattice;
  lattice.box_min = {0, 0, 0};
  lattice.box_max = {1, 1, 1};
  lattice.spacing = 0.1;
  lattice.radius = 0.05;
  lattice.kind = LatticeSpec::Kind::SimpleCubic;
  CHECK(lattice_sites(lattice).size() == 1000);  // 10 per axis: 0.05, 0.15, ..., 0.95

  lattice.radius = 0.04;
  lattice.kind = LatticeSpec::Kind::BodyCentredCubic;
  // Corners at 0.04 + 0.1 i <= 0.96: 10 per axis; centres at 0.09 + 0.1 i <= 0.96: 9 per axis.
  std::vector<Vec3d> sites = lattice_sites(lattice);
  CHECK(sites.size() == 1000 + 729);
  // Bottom layer first: corner layer, then the first centre layer.
  CHECK(sites[0] == Vec3d{0.04, 0.04, 0.04});
  CHECK(sites[100][2] == Approx(0.09));

  lattice.box_max = {0.2, 0.3, 0.1};
  lattice.kind = LatticeSpec::Kind::SimpleCubic;
  lattice.radius = 0.05;
  CHECK(lattice_sites(lattice).size() == 2 * 3 * 1);

  std::vector<SphereSpec> spheres;
  lattice.box_max = {1, 1, 1};
  lattice.radius = 0.045;  // not touching, so rounding cannot make neighbours overlap
  lattice.max_count = 150;
  lattice.velocity = {0, 0, 2};
  append_lattice(lattice, spheres);
  REQUIRE(spheres.size() == 150);
  CHECK(spheres[99].position[2] == Approx(0.045));  // the first 100 fill the bottom layer
  CHECK(spheres.back().position[2] == Approx(0.145));
  CHECK(!any_overlap(spheres));
  CHECK(spheres[0].velocity == Vec3d{0, 0, 2});
}

TEST_CASE("200,000 spheres fill in seconds, overlap-free") {
  FillSpec fill = box_fill(200000, 0.005, 0.005, 1);
  fill.box_max = {0.8, 0.8, 0.82};  // about 20 % solid
  std::vector<SphereSpec> spheres;
  auto start = std::chrono::steady_clock::now();
  append_fill(fill, spheres);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE(spheres.size() == 200000);
  CHECK(seconds < 10);
  // Overlap check of all of them through an independent grid pass.
  SphereGrid grid(0.01, fill.box_min, fill.box_max, spheres.size());
  int overlaps = 0;
  for (const SphereSpec& s : spheres) {
    overlaps += grid.find_overlap(s.position, s.radius) >= 0;
    grid.insert(s.position, s.radius);
  }
  CHECK(overlaps == 0);
}

TEST_CASE("a fill of 100,000 spheres or more is stored in the order of its cells", "[case][fill]") {
  // Consecutive spheres' distance, median: placed at random they lie about a third of the box
  // apart (0.4 m here); in cell order a few diameters (touching cells are within 2 x 20 mm).
  auto median_step = [](const std::vector<SphereSpec>& s) {
    std::vector<double> d;
    for (size_t i = 1; i < s.size(); ++i) {
      double dx = s[i].position[0] - s[i - 1].position[0], dy = s[i].position[1] - s[i - 1].position[1],
             dz = s[i].position[2] - s[i - 1].position[2];
      d.push_back(std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
    return d[d.size() / 2];
  };
  for (int count : {kFillInCellOrder - 1, kFillInCellOrder}) {
    FillSpec fill = box_fill(count, 0.005, 0.005, 3);
    fill.box_max = {1.0, 1.0, 0.35};  // about 15 % solid
    std::vector<SphereSpec> spheres;
    append_fill(fill, spheres);
    REQUIRE(spheres.size() == size_t(count));
    std::vector<SphereSpec> first;
    fill.count = 1;
    append_fill(fill, first);  // the first sphere placed
    bool in_cells = count >= kFillInCellOrder;
    INFO(count << " spheres: median step " << median_step(spheres) << " m");
    CHECK((median_step(spheres) < 0.05) == in_cells);
    // Below the threshold the placement order stands: the first sphere is the first placed.
    CHECK((spheres[0].position == first[0].position) == !in_cells);
  }
}

TEST_CASE("a template lattice packs aligned stalks with per-axis spacing", "[case][lattice][clump]") {
  std::string text =
      "[simulation]\nend_time = 1\nrayleigh_fraction = 0.35\n"
      "[[material]]\npreset = \"cotton_stalk\"\n"
      "[[interaction]]\nmaterials = [\"cotton_stalk\", \"cotton_stalk\"]\npreset = [\"cotton_stalk\", \"cotton_stalk\"]\n"
      "[[template]]\nname = \"stalk\"\nbuiltin = \"cotton_stalk_coarse\"\n"
      // stalk axis z -> x: a quarter turn about y
      "[[lattice]]\ntemplate = \"stalk\"\nmaterial = \"cotton_stalk\"\ntype = \"sc\"\n"
      "min = [0, 0, 0]\nmax = [0.4, 0.1, 0.2]\nspacing = [0.082, 0.0105, 0.0105]\n"
      "orientation = [0.7071067811865476, 0, 0.7071067811865476, 0]\n";
  CaseSpec spec = load_case_from_string(text, "stalks.toml");
  // Along x: floor((0.4 - 0.08) / 0.082) + 1 = 4; y: floor((0.1 - 0.01) / 0.0105) + 1 = 9;
  // z: floor((0.2 - 0.01) / 0.0105) + 1 = 19 (hull 80 x 10 mm).
  CHECK(spec.bodies.size() == 4 * 9 * 19);
  CHECK(spec.spheres.empty());
  for (const BodySpec& b : spec.bodies) {
    CHECK(b.position[0] >= 0.04 - 1e-9);
    CHECK(b.position[0] <= 0.36 + 1e-9);
    CHECK(b.position[2] >= 0.005 - 1e-9);
  }
  // Too tight a spacing overlaps bodies and is refused, naming the lattice.
  std::string tight = text;
  tight.replace(tight.find("0.0105, 0.0105"), 14, "0.008, 0.0105");
  CHECK_THROWS_WITH(load_case_from_string(tight, "stalks.toml"),
                    Catch::Contains("stalks.toml:") && Catch::Contains("overlaps"));
}
