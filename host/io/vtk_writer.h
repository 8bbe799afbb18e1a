// ParaView-readable frames as XML VTK PolyData (.vtp, raw appended binary) and their time
// series (.pvd, which ParaView reads only with XML pieces):
// - particles: one vertex per sphere with radius, speed, id, body_id (the rigid body a
//   sub-sphere belongs to; a lone sphere is its own body), velocity, angular velocity, force
//   (a Glyph filter scaled by "radius" shows the spheres);
// - walls: every wall's surface at the frame's time (planes as patches across the domain,
//   cylinders as 48-sided tubes, rectangles, box faces and mesh triangles), cell data wall_index
//   (the wall's place among the case's named walls, as in wall_forces.csv).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "engine/backend.h"
#include "engine/model.h"

namespace repose {

// body_ids: one per particle (empty: each particle is its own body).
void write_vtk_frame(const std::string& path, const HostState& state, double time,
                     const std::vector<uint32_t>& body_ids = {});

// Where planes are drawn: the box around the particles at the start and every bounded wall.
struct Bounds {
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  void add(const Vec3d& p);
  bool empty() const { return lo[0] > hi[0]; }
};
Bounds drawing_bounds(const Model& model);
void write_wall_frame(const std::string& path, const Model& model, double time, const Bounds& bounds);

// A .pvd collection: file names relative to the .pvd's folder, with their times.
struct SeriesEntry {
  double time = 0;
  std::string file;
};
void write_pvd(const std::string& path, const std::vector<SeriesEntry>& entries);

}  // namespace repose
