// Where a heap angle's scatter comes from, on heaps whose causes are known: smooth cones of
// different slopes differ only heap to heap (no camera side, no fit noise); one rough cone seen
// from several sides differs only by camera side and fit.
#include <catch2/catch.hpp>

#include <cmath>

#include "measure/heap_scatter.h"
#include "measure/heap_views.h"
#include "synthetic_heaps.h"

using namespace repose;
using namespace repose::test;

TEST_CASE("spread_of: mean, sample sd and SE of the finite values", "[heap]") {
  const SampleSpread s = spread_of({1.0, 2.0, 3.0, 4.0, std::nan("")});
  CHECK(s.n == 4);
  CHECK(s.mean == Approx(2.5));
  CHECK(s.sd == Approx(std::sqrt(5.0 / 3.0)));
  CHECK(s.se() == Approx(std::sqrt(5.0 / 3.0) / 2.0));
  CHECK(std::isnan(spread_of({1.0}).sd));
  CHECK(std::isnan(spread_of({}).mean));
}

TEST_CASE("smooth cones of three slopes: the whole scatter is heap to heap", "[heap]") {
  HeapReadingOptions options;
  options.views = 4;
  std::vector<HeapReading> readings;
  for (double slope : {26.0, 30.0, 34.0}) {
    readings.push_back(read_heap(cone_shell(0.1, slope, 0.004), options));
    const HeapReading& r = readings.back();
    INFO("slope " << slope << ": front " << r.front << ", views " << r.views_mean << " (sd " << r.views_sd
                  << "), turned sd " << r.turned_sd);
    // A cone's silhouette is the same from every side: the 0.5 degree of the angle tests.
    CHECK(std::abs(r.front - slope) < 0.5);
    CHECK(std::abs(r.views_mean - slope) < 0.5);
    CHECK(r.views_sd < 0.3);
    CHECK(r.turned_sd < 0.3);
    CHECK(r.height == Approx(0.108).margin(0.001));  // apex sphere top above the base ring bottom: 0.1 + 2 r
  }
  const HeapScatter s = heap_scatter(readings);
  CHECK(s.front.n == 3);
  CHECK(s.front.sd == Approx(4.0).margin(0.3));  // the slopes' own sd
  CHECK(s.one_view_sd == Approx(4.0).margin(0.3));  // every view of a cone reads its slope
  CHECK(s.packing_sd == Approx(4.0).margin(0.3));
  CHECK(s.fit_sd < 0.3);
  CHECK(s.camera_sd < 0.3);
}

TEST_CASE("one rough cone seen from turned cameras: no heap-to-heap scatter, only camera and fit", "[heap]") {
  const std::vector<Sphere> heap = rough_cone(0.08, 30.0, 0.008, 3);
  HeapReadingOptions options;
  options.views = 8;
  std::vector<HeapReading> readings;
  // The same heap photographed by cameras at other azimuths: as if refilled, but only the camera moved.
  for (double azimuth : {0.0, 40.0, 80.0, 120.0})
    readings.push_back(read_heap(turned_heap(heap, heap_centre(heap), azimuth), options));
  const HeapScatter s = heap_scatter(readings);
  INFO("front sd " << s.front.sd << ", views mean sd " << s.views_mean.sd << ", fit " << s.fit_sd << ", camera "
                   << s.camera_sd << ", packing " << s.packing_sd);
  CHECK(s.front.sd > 0);
  CHECK(s.fit_sd > 0);
  // The views' mean sees the same heap whichever camera starts it: its spread is far below the front's.
  CHECK(s.views_mean.sd < 0.5 * s.front.sd);
  CHECK(std::abs(s.front.mean - 30.0) < 1.5);
}

TEST_CASE("heap reading refuses bad options", "[heap]") {
  const std::vector<Sphere> heap = cone_shell(0.05, 30.0, 0.005);
  HeapReadingOptions options;
  options.side = "middle";
  CHECK_THROWS_WITH(read_heap(heap, options), Catch::Contains("left, right or both"));
  options = {};
  options.views = 0;
  CHECK_THROWS_WITH(read_heap(heap, options), Catch::Contains("at least 1"));
  options = {};
  options.turn_deg = 0;
  CHECK_THROWS_WITH(read_heap(heap, options), Catch::Contains("(0, 45]"));
  CHECK_THROWS_WITH(read_heap({}, {}), Catch::Contains("no spheres"));
  HeapReadingOptions one;
  one.views = 1;
  CHECK_THROWS_WITH(heap_scatter({read_heap(heap, one), read_heap(heap, {})}), Catch::Contains("different views"));
}
