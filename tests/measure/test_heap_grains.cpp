// Which grains are the heap (measure/heap_grains.h): those resting on the floor, directly or
// through touching grains; grains held above it (on a hopper's cone, on a gate) are not, though
// a front view of every grain would draw them on the heap's outline.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "measure/heap_angle.h"
#include "measure/heap_grains.h"

using namespace repose;

namespace {

constexpr double kR = 0.005;  // m, the large heap's grains

// A 30 deg cone 0.1 m high of touching grains on a cubic lattice (spacing 2r), on the floor z = 0.
std::vector<Sphere> cone() {
  std::vector<Sphere> s;
  const double height = 0.1, slope = std::tan(30.0 * M_PI / 180.0);
  for (int k = 0; k < 20; ++k)
    for (int j = -40; j <= 40; ++j)
      for (int i = -40; i <= 40; ++i) {
        glm::dvec3 c{2 * kR * i, 2 * kR * j, kR + 2 * kR * k};
        if (c.z - kR <= height - slope * std::hypot(c.x, c.y)) s.push_back({c, kR});
      }
  return s;
}

// Grains a hopper left above the heap: a ring of touching pairs on its cone at 0.3 m, one grain on
// a gate at 0.25 m.
std::vector<Sphere> left_above() {
  std::vector<Sphere> s;
  for (int a = 0; a < 12; ++a) {
    double phi = a * M_PI / 6;
    glm::dvec3 c{0.15 * std::cos(phi), 0.15 * std::sin(phi), 0.3};
    s.push_back({c, kR});
    s.push_back({c + glm::dvec3(0, 0, 2 * kR), kR});
  }
  s.push_back({{0.2, 0.0, 0.25}, kR});
  return s;
}

}  // namespace

TEST_CASE("heap grains: what rests on the floor through touching grains is the heap; grains held above are not",
          "[measure][heap]") {
  std::vector<Sphere> heap = cone(), all = heap, above = left_above();
  all.insert(all.end(), above.begin(), above.end());
  all.push_back({{0.5, 0.0, kR * 0.99}, kR});  // a grain that ran out over the floor: the heap's
  std::vector<bool> resting = resting_on_floor(all, 0.0);
  size_t kept = size_t(std::count(resting.begin(), resting.end(), true));
  CHECK(kept == heap.size() + 1);
  for (size_t i = heap.size(); i < heap.size() + above.size(); ++i) CHECK_FALSE(resting[i]);
  CHECK(resting.back());

  // The same for any order of the grains.
  std::vector<Sphere> reversed(all.rbegin(), all.rend());
  std::vector<bool> again = resting_on_floor(reversed, 0.0);
  CHECK(std::equal(again.begin(), again.end(), resting.rbegin()));

  // A grain 0.2 of a radius clear of the heap's top grain is apart; touching it, it is the heap's.
  std::vector<Sphere> top = heap;
  auto highest = *std::max_element(heap.begin(), heap.end(), [](auto& a, auto& b) { return a.centre.z < b.centre.z; });
  top.push_back({highest.centre + glm::dvec3(0, 0, 2.2 * kR), kR});
  CHECK_FALSE(resting_on_floor(top, 0.0).back());
  top.back().centre.z = highest.centre.z + 1.98 * kR;
  CHECK(resting_on_floor(top, 0.0).back());
}

TEST_CASE("heap grains: the front view of the heap alone measures its height and slope; with the grains above it does not",
          "[measure][heap]") {
  std::vector<Sphere> all = cone(), above = left_above();
  all.insert(all.end(), above.begin(), above.end());
  std::vector<bool> resting = resting_on_floor(all, 0.0);
  std::vector<Sphere> heap;
  for (size_t i = 0; i < all.size(); ++i)
    if (resting[i]) heap.push_back(all[i]);
  HeapAngleOptions options;
  options.floor_z = 0.0;
  HeapAngle measured = measure_heap_angle(heap, options), everything = measure_heap_angle(all, options);
  // The top grain sits on the lattice's 0.1 m layer: its top at 0.11 m (to a pixel).
  CHECK(measured.heap_height == Approx(0.1 + 2 * kR).margin(0.2 * kR));
  CHECK(everything.heap_height > 0.3);
  // A 30 deg cone of 10 mm steps: the fit through its staircase within 3 deg.
  REQUIRE(measured.left.valid);
  REQUIRE(measured.right.valid);
  CHECK(measured.mean_deg == Approx(30.0).margin(3.0));
  CHECK_FALSE(everything.mean_deg == Approx(30.0).margin(3.0));  // off, or no slope at all (NaN)
}

TEST_CASE("heap grains: a clump rests as a whole, though its spheres need not touch", "[measure][heap]") {
  // A cabbage-like body: a core on the floor and a vein sphere clear of it above; a lone grain
  // clear above both.
  std::vector<Sphere> s = {{{0, 0, 0.08}, 0.08}, {{0, 0, 0.18}, 0.012}, {{0, 0, 0.25}, 0.012}};
  std::vector<bool> alone = resting_on_floor(s, 0.0);
  CHECK(alone == std::vector<bool>{true, false, false});
  std::vector<bool> bodies = resting_on_floor(s, 0.0, {7, 7, 9});
  CHECK(bodies == std::vector<bool>{true, true, false});
  CHECK_THROWS_AS(resting_on_floor(s, 0.0, {7, 7}), std::invalid_argument);
}
