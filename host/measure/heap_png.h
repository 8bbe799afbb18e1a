// The picture of a heap-angle measurement, like the seeds' figures: silhouette, outer boundary,
// the boundary points used, and the fitted slope lines, saved as a PNG.
#pragma once
#include <string>

#include "measure/heap_angle.h"

namespace repose {

// Colours: background white, silhouette light grey, outer boundary black, left fit red, right
// fit blue, the boundary points used by the fits orange (on top), floor green. Throws
// std::runtime_error if the file cannot be written.
void write_heap_angle_png(const std::string& path, const HeapAngle& measurement);

}  // namespace repose
