// ParaView-readable frames: legacy VTK PolyData (binary), one vertex per sphere with radius,
// velocity, angular velocity, speed, force and id as point data (use a Glyph filter with
// scale by "radius" to see spheres).
#pragma once
#include <string>

#include "engine/backend.h"

namespace repose {

void write_vtk_frame(const std::string& path, const HostState& state, double time);

}  // namespace repose
