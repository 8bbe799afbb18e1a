// The picture of a heap-angle measurement, like the studies' figures: silhouette, outline, the
// points used and the fitted slope lines, with axes, scale and the measured angle, as a PNG.
#pragma once
#include <string>

#include "measure/heap_angle.h"

namespace repose {

// A chart at equal scale with axes in metres (`horizontal` names the image's horizontal axis),
// the measured angle in its title: silhouette light grey, its top outline black, left fit red,
// right fit blue (drawn from the floor to the crest height, clipped to the picture), the outline
// points the fits used orange, floor green. Throws std::runtime_error if it cannot be written.
void write_heap_angle_png(const std::string& path, const HeapAngle& measurement, const std::string& horizontal = "x");

}  // namespace repose
