// ParaView-readable frames as XML VTK PolyData (.vtp, raw appended binary) and their time
// series (.pvd, which ParaView reads only with XML pieces):
// - particles: one vertex per sphere with radius, speed, id, body_id (the rigid body a
//   sub-sphere belongs to; a lone sphere is its own body), material (its index among the case's
//   materials), orientation (its body's principal frame to the world, a unit quaternion w, x, y,
//   z; 1, 0, 0, 0 for a lone sphere), velocity, angular velocity, force (a Glyph filter scaled by
//   "radius" shows the spheres);
// - contacts: the force network, one line between the centres of each touching pair of spheres
//   of different bodies, with cell data normal_force (N, > 0 pushes them apart) and force (on the
//   first sphere of the pair, N): a Tube filter scaled by normal_force shows the force chains;
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

// What each particle is: its body (empty: each particle is its own body) and its material.
struct ParticleLabels {
  std::vector<uint32_t> body_ids, materials;
};
ParticleLabels particle_labels(const Model& model);

void write_vtk_frame(const std::string& path, const HostState& state, double time, const ParticleLabels& labels = {});

// One line of the force network: spheres i < j touching (their surfaces overlap), the normal
// force between them (on i along the unit normal from j to i) and the whole force on i.
struct ContactLine {
  uint32_t i = 0, j = 0;
  float normal_force = 0;
  gpu::vec4 force{0.0f};
};
// The touching pairs of the contact list (state.row_start, partner) with their forces (one per
// list entry, Simulation::contact_forces()), in list order; pairs within one body are not contacts.
std::vector<ContactLine> touching_pairs(const HostState& state, const std::vector<gpu::vec4>& contact_forces,
                                        const ParticleLabels& labels);
void write_contact_frame(const std::string& path, const HostState& state, const std::vector<ContactLine>& lines,
                         double time);

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
