// A case turned into what the kernels consume: float particle arrays, the material-pair table
// with EDEM's derived constants, walls expanded to planes and cylinders with their motion, and
// the resolved numerical settings (dt, skin, grid).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "repose_shared.h"

namespace repose {

struct ModelWall {
  uint32_t kind = gpu::kWallPlane;
  uint32_t material = 0;
  // plane: point, normal; cylinder: base, axis; rectangle: centre, normal, edge axes u and v;
  // triangle: vertices p0 p1 p2, unit normal p3 (gpu::WallState describes the same slots).
  Vec3d p0{}, p1{}, p2{}, p3{};
  double radius = 0, height = 0;
  double half_u = 0, half_v = 0;          // rectangle half extents along p2, p3
  uint32_t mesh_id = 0;                   // triangle: which [[wall]] mesh
  std::array<uint32_t, 3> vertex_ids{};   // triangle: the mesh's shared vertex ids
  WallMotion motion;
  std::string name;        // the case's wall name, with a face suffix for boxes
  int spec_index = 0;      // which [[wall]] it came from
  uint32_t group = 0;      // its named wall: wall_group_names()[group]
  uint32_t moving_row = 0; // 0 without motion, else 1 + its place among the moving walls (walls.h wall_at)
};

// True when the motion moves its wall at some time (translation or rotation): such a wall has a
// row per step of a batch; any other wall's row never changes.
bool has_motion(const WallMotion& m);

struct Model {
  std::string case_path;
  uint32_t n_particles = 0;
  uint32_t n_materials = 0;
  std::vector<gpu::vec4> pos, vel, omega;  // w: radius, 1/mass, 1/inertia
  std::vector<uint32_t> material;
  std::vector<gpu::PairParams> pairs;      // [M*M]
  // Rigid bodies (clumps). Empty when every particle is a free sphere; otherwise every particle
  // is a sub-sphere of exactly one body (a lone sphere is a one-sphere body), bodies' spheres
  // contiguous and in body order, and pos/vel/omega above are derived by body_place.
  std::vector<gpu::Body> bodies;
  std::vector<gpu::SubSphere> subs;
  std::vector<gpu::BodyPart> parts;        // each body's parts, in body order (body_parts)
  std::vector<ModelWall> walls;
  std::vector<uint32_t> moving_walls;      // the walls with a motion, ascending (ModelWall::moving_row)
  uint32_t n_wall_groups = 0;              // named walls (wall_group_names)
  // The wall grid (engine/wall_grid.h): gpu::WallGrid's words and its buckets; empty and 0 when
  // every sphere tests every wall.
  std::vector<uint32_t> wall_grid;
  uint32_t wall_table_size = 0;
  double dt = 0;
  double rayleigh_time = 0;
  double end_time = 0;
  double output_interval = 0;
  double checkpoint_interval = 0;  // s between checkpoints of `repose run` (0: none)
  bool vtk = true;
  Vec3d gravity{};
  Integrator integrator = Integrator::VelocityVerlet;
  uint32_t flags = 0;            // contact options (gpu::kFlag...)
  double large_radius = 3.0e38;  // particles above it use the large bucket (neighbour.h)
  double skin = 0;
  double cell = 0;               // hash cell edge
  uint32_t table_size = 0;       // hash buckets
  uint32_t max_interval = 0;     // forced rebuild interval (walls that move), 0: none
  uint32_t still_interval = 0;   // the same while no wall moves ([neighbour] rebuild_interval)
  double total_mass = 0;          // of the particles that move (fixed ones are excluded)
  double air_drag = 0;           // extension air_drag: 0.5 rho_air C_d pi (SimPush::air_drag), 0: off
  double rolling_damping = 0;    // kFlagRollingSpring: eta_r (SimPush::rolling_damping)

  // A wall's state at time t (prescribed motion evaluated on the host, in double).
  gpu::WallState wall_state(size_t w, double t) const;
  // The case's walls by name (a mesh's triangles and a box's faces are separate model walls):
  // for each model wall, the index of its group; group_names()[k] names group k.
  std::vector<std::string> wall_group_names() const;
  std::vector<size_t> wall_groups() const;
};

// Throws CaseError-style messages naming the case file when the case cannot be simulated.
Model build_model(const CaseSpec& spec);

// The pair constants computed from the materials and the interaction (the rows of
// REPOSE_PAIR_PARAMS whose source is `derived`), in double: EDEM's (docs/engineering.md, contact
// law) and the extensions'.
struct DerivedPairConstants {
  double e_star = 0, g_star = 0, damping = 0, cohesion_pi_k = 0;
};
DerivedPairConstants derived_pair_constants(const Material& a, const Material& b, const Interaction& in);
// Every pair constant the kernels read (REPOSE_PAIR_PARAMS), each rounded to float once.
gpu::PairParams pair_params(const Material& a, const Material& b, const Interaction& in);
// Some interaction has spinning friction (kFlagSpinningFriction).
bool needs_spinning_friction(const CaseSpec& spec);

}  // namespace repose
