// The front view from several sides: on an elliptic cone every view's slope follows from the
// ellipse (the silhouette's half-width is the base ellipse's support width across the view), so
// each view is checked against its own closed form. Tolerance 0.5 degree, as for one view.
#include <catch2/catch.hpp>

#include <cmath>

#include "measure/heap_angle.h"
#include "measure/heap_views.h"
#include "synthetic_heaps.h"

using namespace repose;
using namespace repose::test;

namespace {

constexpr double kTolerance = 0.5;  // degrees, the single-view measurement's own

// A cone shell stretched to base semi-axes a (along x) and b (along y), centred at (cx, cy).
std::vector<Sphere> elliptic_cone(double height, double a, double b, double r, double cx, double cy) {
  const double slope = std::atan(height / a) * 180.0 / kPi;  // circular cone of base radius a
  std::vector<Sphere> heap = cone_shell(height, slope, r);
  for (Sphere& s : heap) s.centre = {cx + s.centre.x, cy + s.centre.y * b / a, s.centre.z};
  return heap;
}

}  // namespace

TEST_CASE("several views of an elliptic cone: each view its own slope, the mean theirs", "[heap]") {
  const double h = 0.15, a = 0.26, b = 0.41, r = 0.004;  // 30.0 deg across x, 20.1 deg across y
  const std::vector<Sphere> heap = elliptic_cone(h, a, b, r, 0.3, -0.2);
  const HeapViewsAngle m = measure_heap_angle_views(heap, 6);
  CHECK(m.centre.x == Approx(0.3).margin(0.01));
  CHECK(m.centre.y == Approx(-0.2).margin(0.01));
  REQUIRE(m.azimuth_deg.size() == 6);
  REQUIRE(m.valid_slopes == 12);
  double sum = 0;
  for (size_t k = 0; k < 6; ++k) {
    // The camera turned by psi sees across the horizontal direction (cos psi, sin psi): the
    // base ellipse's half-width there is sqrt(a^2 cos^2 + b^2 sin^2).
    const double psi = m.azimuth_deg[k] * kPi / 180.0;
    const double expected = std::atan(h / std::hypot(a * std::cos(psi), b * std::sin(psi))) * 180.0 / kPi;
    INFO("view " << m.azimuth_deg[k] << " deg: left " << m.left_deg[k] << ", right " << m.right_deg[k] << ", expected "
                 << expected);
    CHECK(std::abs(m.left_deg[k] - expected) < kTolerance);
    CHECK(std::abs(m.right_deg[k] - expected) < kTolerance);
    sum += 2 * expected;
  }
  CHECK(std::abs(m.mean_deg - sum / 12) < kTolerance);
  CHECK(m.sd_deg > 3.0);  // the views differ by ~10 degrees: the spread is reported, not hidden
}

TEST_CASE("view 0 of several is the plain front view", "[heap]") {
  const std::vector<Sphere> heap = rough_cone(0.2, 32.0, 0.006, 11);
  const HeapAngle front = measure_heap_angle(heap);
  const HeapViewsAngle m = measure_heap_angle_views(heap, 4);
  // Same picture up to the shift to the heap axis (pixel grid phase): within a tenth of a degree.
  CHECK(m.left_deg[0] == Approx(front.left.angle_deg).margin(0.1));
  CHECK(m.right_deg[0] == Approx(front.right.angle_deg).margin(0.1));
  for (size_t k = 0; k < 4; ++k) {
    CHECK(std::abs(m.left_deg[k] - 32.0) < 1.0);  // a rough cone is the same all round
    CHECK(std::abs(m.right_deg[k] - 32.0) < 1.0);
  }
  CHECK_THROWS_AS(measure_heap_angle_views(heap, 0), std::invalid_argument);
  CHECK_THROWS_AS(measure_heap_angle_views({}, 3), std::invalid_argument);
}
