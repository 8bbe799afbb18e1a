// The picture of a heap-angle measurement, like the studies' figures: silhouette, outline, the
// points used and the fitted slope lines, with axes, scale and the measured angle, as a PNG.
#pragma once
#include <string>

#include "measure/heap_angle.h"

namespace repose {

// What the picture's title states and which slopes it draws: the headline angle the experiment
// or the command reports (the front view's slope, both slopes' mean, or an estimator over many
// views) and how it was measured, so that the picture and the console say the same number.
struct HeapPictureCaption {
  double angle_deg = 0.0;   // NaN: no angle measured
  std::string measured_as;  // e.g. "the right slope", "the mean of 16 views' slopes"
  bool left = true, right = true;  // the slopes that count: only these are drawn (when valid)
  std::string warning;  // ends the title when not empty: "not settled at 12 s"
};

// The caption of a plain front-view measurement: its two slopes' mean, both drawn.
HeapPictureCaption front_view_caption(const HeapAngle& measurement);
// The caption of one slope (`side`: "left", "right" or "both") of the front view.
HeapPictureCaption slope_caption(const HeapAngle& measurement, const std::string& side);

// A chart at equal scale with axes in metres (`horizontal` names the image's horizontal axis),
// the caption's angle in its title and this front view's slopes under it: silhouette light grey,
// its top outline black, left fit red, right fit blue (drawn from the floor to the crest height,
// clipped to the picture), the outline points the fits used orange, floor green. The legend lists
// only what is drawn. Throws std::runtime_error if it cannot be written.
void write_heap_angle_png(const std::string& path, const HeapAngle& measurement, const std::string& horizontal,
                          const HeapPictureCaption& caption);
inline void write_heap_angle_png(const std::string& path, const HeapAngle& measurement,
                                 const std::string& horizontal = "x") {
  write_heap_angle_png(path, measurement, horizontal, front_view_caption(measurement));
}

}  // namespace repose
