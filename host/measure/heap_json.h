// The JSON of a heap's measurement, one schema for `repose heap-angle --json` and the repose
// experiment's repose.json: slopes, profiles, views around the heap and 3D sectors.
#pragma once
#include <nlohmann/json.hpp>

#include "measure/heap_angle.h"
#include "measure/heap_profile.h"
#include "measure/heap_views.h"

namespace repose {

nlohmann::ordered_json slope_json(const SlopeFit& fit);
nlohmann::ordered_json profile_json(const SlopeProfile& profile);
nlohmann::ordered_json views_json(const HeapViewsAngle& views);
nlohmann::ordered_json axisymmetric_json(const AxisymmetricHeapAngle& heap);

}  // namespace repose
