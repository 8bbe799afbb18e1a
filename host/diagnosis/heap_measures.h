// What a diagnosed heap reports, by measure name, from one simulated repose rig
// (host/experiments/repose.h): the angle and the bed height, and the shape of the heap in the
// same picture (measure/heap_profile.h): its height, its run-out and its profile's convexity,
// taken on the case's [experiment] heap_side (the two sides' mean for "both").
#pragma once
#include <map>
#include <string>
#include <vector>

#include "experiments/repose.h"

namespace repose {

// Every heap measure, in the order data files list them: repose_angle, bed_height, heap_height,
// runout, profile_convexity.
const std::vector<std::string>& heap_measure_names();

// All of them for one heap. A side whose profile could not be measured (no slope) gives a
// convexity of 0, as a flat heap would; its run-out is still measured.
std::map<std::string, double> heap_measures(const ReposeResult& heap, const std::string& heap_side);

// The same from a measured picture's results (repose heap-angle on a user's own heap): the angle of
// the side asked for (the valid sides' mean for "both"), the bed height of a bed before the lift.
std::map<std::string, double> heap_measures(double angle_deg, double bed_height, const HeapProfile& profile,
                                            const std::string& heap_side);

}  // namespace repose
