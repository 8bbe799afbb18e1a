// Wall meshes Repose makes itself, written as ASCII STL (`repose mesh`), so that a shipped case's
// geometry comes from a documented command rather than a download: a conical hopper (a frustum
// surface open at both ends, axis z, outlet at z = 0), in whatever length unit its numbers are
// (the case's `scale` turns them into metres).
#pragma once
#include <ostream>
#include <string>

#include "geometry/stl.h"

namespace repose {

// `sides` quadrilaterals, each two triangles, between the outlet circle (radius outlet_radius at
// z = 0) and the top circle (top_radius at z = height); corners at angles 2 pi k / sides from +x.
TriangleMesh hopper_mesh(double top_radius, double outlet_radius, double height, int sides);

// ASCII STL: "solid NAME", one facet per triangle with its unit normal, coordinates as %.9g.
void write_ascii_stl(std::ostream& out, const TriangleMesh& mesh, const std::string& name);

}  // namespace repose
