// Where a heap angle's fill-to-fill scatter comes from. A lab photographs each heap once and fits
// a line to its outline; over refilled heaps the reading scatters for three reasons: the heap
// itself differs (the packing), the camera stands on another side of it, and the line is fitted
// to the outline of a few bodies. Saved heaps (heap.csv) are re-measured here at no cost: each
// heap from many sides and from cameras turned by a degree or two, which a lab cannot tell apart
// from its own front view.
#pragma once
#include <string>
#include <vector>

#include "geometry/sphere.h"
#include "measure/heap_angle.h"

namespace repose {

struct HeapReadingOptions {
  HeapAngleOptions angle;     // the front camera's view axis, fit band and floor
  std::string side = "both";  // the slope a photograph's reading takes: "left", "right" or "both" (their mean)
  // Cameras over half a turn about the heap's axis (heap_views.h): a rig without a preferred side
  // (a cylinder lift) looks the same from each. 1: a rig with one front (a box, a bucket).
  int views = 16;
  double turn_deg = 2.0;  // the front camera turned by +-turn and +-turn/2: the fit's own noise
};

struct HeapReading {
  double front = 0.0;       // the photograph: `side` of the front view (NaN: no slope)
  double views_mean = 0.0;  // the reading of every view, averaged (the front's own with views 1)
  double views_sd = 0.0;    // sd of one camera's reading between the views of this heap (0 for views 1)
  double turned_sd = 0.0;   // sd of the reading between the front camera and its four small turns
  std::vector<double> per_view;  // each view's reading, views 0 .. views - 1 (the front alone for views 1)
  double height = 0.0;      // front view's heap height, m
  double runout = 0.0;      // front view's crest-to-toe distance on `side` (both: the two sides' mean), m
};

// Throws std::invalid_argument for an empty heap, views < 1, a side that is not left, right or
// both, or a turn outside (0, 45] degrees.
HeapReading read_heap(const std::vector<Sphere>& heap, const HeapReadingOptions& options);

struct SampleSpread {
  int n = 0;  // finite values
  double mean = 0.0, sd = 0.0;  // sample sd (n - 1); NaN when n < 1 (mean) or n < 2 (sd)
  double se() const;            // sd / sqrt(n)
};
SampleSpread spread_of(const std::vector<double>& values);  // NaNs are left out

// The readings of refilled heaps of one rig (all with the same views), and one photograph's
// variance split by cause. one_view: the fill-to-fill variance of one camera's reading, pooled
// over the views (each view of a rig without a preferred side is a front view; the front's own sd
// rests on one camera and is far less certain); the front alone for views 1. fit^2: the mean
// within-heap variance between small turns; camera^2: the mean within-heap variance between
// views, less the fit's; packing^2 (the heap itself, refill to refill): one_view^2 less both.
// Each floored at 0; views 1: camera 0.
struct HeapScatter {
  SampleSpread front, views_mean, height, runout;
  double one_view_sd = 0.0;
  double fit_sd = 0.0, camera_sd = 0.0, packing_sd = 0.0;
};
HeapScatter heap_scatter(const std::vector<HeapReading>& readings);

}  // namespace repose
