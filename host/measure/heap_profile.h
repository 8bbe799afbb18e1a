// The shape of a heap's surface in the same front-view picture its angle is measured from
// (measure_heap_angle): how high the heap stands, how far it runs out, and whether its slope bulges
// or sags. Cohesion and rolling resistance both steepen a heap; they differ in its shape. Moist,
// cohesive grains hold a rounded crest and stop in a steep toe (the profile bulges above the
// straight line from crest to toe), while dry grains held by rolling resistance run out in a thin
// tail (the profile sags below it) and a cohesive heap runs out less far for its angle.
#pragma once
#include <string>

#include "measure/heap_angle.h"

namespace repose {

struct SlopeProfile {
  bool valid = false;
  std::string problem;  // why not valid
  // Horizontal distance from the crest (HeapAngle::crest) to the toe: the far edge of the last
  // picture column, walking away from the crest, that is contiguous with the heap (a grain that
  // rolled away beyond a gap does not count). m.
  double runout = 0.0;
  double toe = 0.0;  // horizontal coordinate of that edge, m
  // The curvature of the profile as its bulge: a parabola z = a + b u + c u^2 fitted to the profile
  // columns between band_low and band_high of the heap height, its largest rise above the chord
  // of the fitted span (-c L^2 / 4) over the height that chord falls (|b| L): -c L / (4 |b|).
  // Positive: convex (a rounded crest, a steep toe); negative: concave (a tail of run-out grains);
  // 0: a straight slope. Dimensionless, so heaps of any size compare.
  double convexity = 0.0;
  size_t points = 0;  // profile columns fitted
};

struct HeapProfileOptions {
  double band_low = 0.02;   // the parabola sees the crest and the toe, but not the floor layer's
  double band_high = 0.98;  // column tops or the single highest grain
};

struct HeapProfile {
  double height = 0.0;  // top of the profile above the floor, m (HeapAngle::heap_height)
  SlopeProfile left, right;
};

// From the measured picture: no further rendering. A side with fewer than three profile columns in
// the band, or without a fall across it, is reported as not valid.
HeapProfile measure_heap_profile(const HeapAngle& heap, const HeapProfileOptions& options = {});

}  // namespace repose
