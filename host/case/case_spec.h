// What a case file says, in SI units, after parsing and validation: the engine's input.
// Every element remembers the line of the case file it came from, so that errors found later
// (overlaps, an unstable time step) can still name the file, key and line.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/clump.h"
#include "util/math.h"

namespace repose {

// Where in a case file a value came from: "cases/box.toml", key "fill[0].count", line 12.
struct SourceRef {
  std::string file;
  std::string key;
  int line = 0;
};

struct Material {
  std::string name;
  double density = 0;        // kg/m^3
  double youngs_modulus = 0; // Pa; the file gives Young's or shear modulus, the other is derived
  double shear_modulus = 0;  // Pa; E = 2 G (1 + nu)
  double poisson = 0;
  SourceRef where;
};

// The optional keys of an [[interaction]], one row each: the key, also the Interaction field of that
// name, its default and its check (case_reader_materials.cpp). A per-pair constant of the contact
// law that a case gives is a row here and a row of the same name in the kernels' pair table
// (REPOSE_PAIR_PARAMS, shaders/repose_shared.h, source interaction). Checks:
//   NonNegative  a number >= 0
//   Switch       true or false (the field holds 1 or 0)
#define REPOSE_INTERACTION_OPTIONS(X) \
  X(spinning_friction, 0, NonNegative)        /* torque mu_spin R* |Fn| against the spin about n (0: off) */ \
  X(viscoelastic_time, 0, NonNegative)        /* s, extension restitution_velocity: damping A Sn vn on top of EDEM's (0: off) */ \
  X(cohesion_energy_density, 0, NonNegative)  /* J/m^3, extension cohesion: EDEM linear cohesion F = k pi R* dn (0: off) */ \
  X(tangential_damping, 1, Switch)            /* the tangential dashpot: on (EDEM) or off (LIGGGHTS tangential_damping off) */

// Contact parameters for one pair of materials (symmetric), EDEM's "interaction" table.
struct Interaction {
  int material_a = 0, material_b = 0;  // indices into CaseSpec::materials
  double restitution = 0;              // (0, 1]
  double static_friction = 0;          // >= 0
  double rolling_friction = 0;         // >= 0
#define REPOSE_INTERACTION_FIELD(name, fallback, check) double name = fallback;
  REPOSE_INTERACTION_OPTIONS(REPOSE_INTERACTION_FIELD)
#undef REPOSE_INTERACTION_FIELD
  SourceRef where;
};

struct SphereSpec {
  Vec3d position{};
  Vec3d velocity{};
  Vec3d angular_velocity{};
  double radius = 0;
  int material = 0;
  bool fixed = false;  // takes part in contacts, never moves (infinite mass; LIGGGHTS fix freeze)
  SourceRef where;  // the [[sphere]], [[fill]] or [[lattice]] entry that made it
};

// A clump template ([[template]]): rigid sub-spheres in the template frame, from one of the
// shipped templates or a sphere CSV. Mass properties come from the union volume and the body's
// material density, or from an explicit mass (the union's centre and inertia scaled to it).
struct TemplateSpec {
  std::string name;
  std::string file;  // the sphere CSV as the case names it ("" for a builtin template)
  ClumpTemplate clump;
  std::optional<double> mass;  // kg at scale 1
  SourceRef where;
};

// One rigid body of a template, placed by a [[clump]] or by a template [[fill]].
struct BodySpec {
  int template_index = 0;
  int material = 0;
  double scale = 1;                               // lengths x scale (mass x scale^3)
  Vec3d position{};                               // where the template's origin goes
  std::array<double, 4> orientation{1, 0, 0, 0};  // unit quaternion (w, x, y, z), template -> world
  Vec3d velocity{};                               // of the centre of mass
  Vec3d angular_velocity{};
  bool fixed = false;                             // never moves (see SphereSpec::fixed)
  SourceRef where;
};

// A region filled at random without overlap (random sequential addition from a seed).
struct FillSpec {
  enum class Shape { Box, Cylinder } shape = Shape::Box;
  Vec3d box_min{}, box_max{};                 // Box
  Vec3d cyl_base{}; Vec3d cyl_axis{0, 0, 1};  // Cylinder: base centre, unit axis,
  double cyl_radius = 0, cyl_height = 0;      //           radius and height
  int count = 0;
  double radius_min = 0, radius_max = 0;  // equal for one size; uniform in [min, max] otherwise
  int template_index = -1;                // >= 0: bodies of this template at random orientations,
  double scale_min = 1, scale_max = 1;    //        scaled uniformly in [min, max]
  int material = 0;
  uint64_t seed = 0;
  Vec3d velocity{};
  bool fixed = false;                     // every sphere or body of the fill is fixed
  // Not a case key: a caller that must place a tight fill (the diagnosis refilling a heap whose
  // grains a candidate made larger) draws every radius first and places the largest first.
  bool largest_first = false;
  SourceRef where;
};

// Spheres on a lattice filling a box: simple cubic or body-centred cubic.
struct LatticeSpec {
  enum class Kind { SimpleCubic, BodyCentredCubic } kind = Kind::SimpleCubic;
  Vec3d box_min{}, box_max{};
  double spacing = 0;  // cube edge
  double radius = 0;
  int material = 0;
  int max_count = 0;   // 0: as many as fit
  Vec3d velocity{};
  // Template lattices: bodies at the sites, all at one orientation, the cell edge per axis
  // (elongated bodies pack aligned, as the cotton-stalk study's 454 stalks in their bucket).
  int template_index = -1;
  Vec3d spacing_xyz{};
  std::array<double, 4> orientation{1, 0, 0, 0};
  double scale = 1;
  bool fixed = false;  // every site's sphere or body is fixed
  SourceRef where;
};

// Prescribed wall motion; the engine evaluates the pose at time t on the host.
struct WallMotion {
  Vec3d velocity{};         // m/s, translation
  double start_time = 0;    // s, motion begins here
  double stop_time = 1e30;  // s, motion ends here
  Vec3d rotation_axis_point{};
  Vec3d rotation_axis{0, 0, 1};
  double angular_rate = 0;  // rad/s about rotation_axis through rotation_axis_point
};

// A triangle mesh wall as placed in the case (STL scaled, then offset), vertices shared.
struct WallMesh {
  std::string file;  // as resolved from the case's folder
  std::vector<Vec3d> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
};

struct WallSpec {
  enum class Type { Plane, Box, Cylinder, Rectangle, Mesh } type = Type::Plane;
  int material = 0;
  // Plane: contact on the side the normal points to.
  Vec3d point{}, normal{0, 0, 1};
  // Box: particles are inside; six inward-facing planes.
  Vec3d box_min{}, box_max{};
  // Cylinder: particles are inside the inner surface; finite along the axis.
  Vec3d base{}, axis{0, 0, 1};
  double radius = 0, height = 0;
  // Box: faces left out ("zmax" for an open top), by the names xmin ... zmax.
  std::vector<std::string> open_faces;
  // Rectangle: centre `point`, unit `normal` (contact on that side), unit in-plane `edge_axis`
  // (side `size[0]` along it, `size[1]` along normal x edge_axis).
  Vec3d edge_axis{1, 0, 0};
  std::array<double, 2> size{0, 0};
  // Mesh: the triangles (shared between copies of the case).
  std::shared_ptr<const WallMesh> mesh;
  WallMotion motion;
  std::string name;  // optional, used in summaries ("floor", "gate")
  SourceRef where;
};

enum class Integrator { VelocityVerlet, SymplecticEuler };
// Engines disagree on these (docs/engineering.md, contact law); the defaults are EDEM's.
enum class CoulombCap { SpringAndDamper, SpringOnly };
enum class NormalAttraction { Allow, Clip };
// ElasticPlastic: EDEM type C, the elastic-plastic spring-dashpot (EPSD) of Ai et al. 2011.
enum class RollingModel { None, ConstantTorque, ElasticPlastic };
enum class RollingOmega { Own, Relative };  // EDEM uses each body's own w, LIGGGHTS the relative w
// The constant torque's lever on a multi-sphere body: the distance from the contact point to the
// body's centre of mass (EDEM, DEM-Engine) or the touching sub-sphere's radius (LIGGGHTS-PUBLIC's
// multisphere). Equal for a lone sphere.
enum class RollingLever { Centre, Sphere };
// What the Coulomb cap and the rolling torque's lever see when cohesion pulls a contact together:
// the net normal force (LIGGGHTS sjkr's default, tangential_reduce off) or the contact's own
// repulsion, which cohesion raises (tangential_reduce on; JKR-like: wet contacts grip harder).
enum class CohesionFriction { Net, Contact };
// The area linear cohesion pulls on: EDEM's Hertz contact area pi R* dn, or LIGGGHTS sjkr's disc
// where the two sphere surfaces intersect (about 2 pi R* dn).
enum class CohesionArea { Hertz, Intersection };

struct ContactOptions {
  CoulombCap coulomb_cap = CoulombCap::SpringAndDamper;
  NormalAttraction normal_attraction = NormalAttraction::Allow;
  RollingModel rolling = RollingModel::ConstantTorque;
  RollingOmega rolling_omega = RollingOmega::Own;
  RollingLever rolling_lever = RollingLever::Centre;  // with rolling_omega Relative: Sphere (R*)
  double rolling_damping = 0.3;  // ElasticPlastic: eta_r, fraction of critical (Ai et al. 2011 use 0.3)
  CohesionFriction cohesion_friction = CohesionFriction::Net;
  CohesionArea cohesion_area = CohesionArea::Hertz;
};

struct TimeSpec {
  // Exactly one of the two is set by the parser; the engine resolves dt.
  std::optional<double> dt;                 // s
  std::optional<double> rayleigh_fraction;  // dt = fraction * Rayleigh time
  double end_time = 0;                      // s
  SourceRef where;                          // dt or rayleigh_fraction
  SourceRef end_where;                      // end_time
};

struct NeighbourSpec {
  double skin = -1;          // m; < 0: half the smallest radius (twice it with clumps: model.cpp)
  int rebuild_interval = 0;  // steps between list rebuilds; 0: automatic
  std::optional<bool> body_broad_phase;  // clumps culled by bounding spheres; unset: where it pays
  std::optional<bool> wall_grid;  // still mesh triangles by grid cell (engine/wall_grid.h); unset: where it pays
};

struct OutputSpec {
  double interval = 0;  // s between VTK frames; 0: no frames
  bool vtk = true;
  double checkpoint_interval = 0;  // s between checkpoint.state files of `repose run`; 0: none
};

// An experiment's own [experiment] keys, as a type the experiment derives from this one
// (host/experiments); the case layer holds them without knowing the type.
struct ExperimentSettings {
  virtual ~ExperimentSettings() = default;
};

// The virtual experiment a case runs with `repose experiment TYPE CASE.toml` ([experiment]). The
// keys besides type and max_time are the experiment's: its reader (case/experiment_keys.h)
// returns them as its settings.
struct ExperimentSpec {
  std::string type;       // "drop", "slide", "roll", "repose", ...; empty: a plain simulation
  double max_time = 5.0;  // s: give up when the measurement has not ended by then
  // Read through settings_of<T> (experiments/experiment.h); shared by copies of the case and never
  // changed in place (edit_settings<T> replaces it by a changed copy).
  std::shared_ptr<const ExperimentSettings> settings;
  SourceRef where;
  SourceRef max_time_where;  // max_time's line (the table's when the default), or --max-time
};

// Extension air_drag: quadratic drag 0.5 rho C_d A v^2 on every sphere (A = pi r^2) and clump
// body (A its silhouette across the velocity). Off when drag_coefficient is 0.
struct AirDragSpec {
  double drag_coefficient = 0;  // C_d (a smooth sphere: ~0.47)
  double air_density = 1.2;     // kg/m^3
  SourceRef where;
};

struct CaseSpec {
  std::string path;  // the case file
  std::string name;  // [simulation] name, else the file's stem
  uint64_t seed = 1;
  Vec3d gravity{0, 0, -9.81};
  Integrator integrator = Integrator::VelocityVerlet;
  ContactOptions contact;
  TimeSpec time;
  NeighbourSpec neighbour;
  OutputSpec output;
  ExperimentSpec experiment;
  AirDragSpec air_drag;
  std::vector<Material> materials;
  std::vector<Interaction> interactions;
  std::vector<SphereSpec> spheres;  // explicit [[sphere]] entries first, then expanded fills/lattices
  std::vector<TemplateSpec> templates;
  std::vector<BodySpec> bodies;     // explicit [[clump]] entries first, then template fills
  std::vector<FillSpec> fills;
  std::vector<LatticeSpec> lattices;
  std::vector<WallSpec> walls;
  // What the case is, for hashing (case_hash): the parsed TOML with overrides applied, without
  // comments or layout, then every file it read (templates, STL meshes) with a hash of its bytes.
  std::string identity;
  // Unusual values found while loading, as "FILE:LINE: KEY: warning: ..." (case/physical_ranges.h);
  // the verbs print them before the run.
  std::vector<std::string> warnings;
};

}  // namespace repose
