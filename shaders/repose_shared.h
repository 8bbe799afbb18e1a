// One header for the C++ host, the C++ kernel twin (kernels_ref/) and every GLSL kernel:
// binding indices, the layouts of every structure that crosses the host/device boundary,
// and the push constants. Mirrored by construction, checked by static_asserts on the host.
#ifndef REPOSE_SHARED_H
#define REPOSE_SHARED_H

#ifdef __cplusplus
#include "glsl_compat.h"
namespace repose::gpu {
#define REPOSE_CONST inline constexpr uint
#else
#define REPOSE_CONST const uint
#endif

// ---- Device buffers: one table, one row per storage buffer (descriptor set 0). ----
// Everything about a buffer follows from its row: the kBind* index below, its GLSL declaration
// (B_name in kernels/glsl_prelude.glsl), the CPU twin's pointers (Buffers::name in
// kernels_ref/cpu_kernels.h, and B_name for the kernel bodies in kernels_ref/twin_kernels.h),
// its size on both backends, whether the host keeps a copy (HostState) and writes it to state
// files (host/engine/buffer_table.h). Adding per-contact state is a row here plus the kernel
// that uses it. Columns:
//   binding (an alias names its target's), Name (kBindName), name (B_name), element type,
//   count:  Particles N, ParticlesPlusOne N+1, ParticlesTwice 2N, Contacts C (the list capacity),
//           ContactsTwice 2C, Transposed C (the used part: trans_start[N]), Buckets T+1, BucketsPlusOne T+2,
//           Pairs M*M, WallRows W + steps_per_batch*(the walls that move), WallSums 3 x the named
//           walls, Bodies B, Control kControlWords, CandidateSlots N*kCandidateSlots, Parts P (the
//           bodies' parts), WallGrid (the wall grid's words, kernels/neighbour.h),
//           ScanBlocks scan_blocks_for(max(N, T+1)) + 1 (the scans' block sums and their total),
//   need:   Always, FullEntries (not with lean entries), Bodies (clumps), RollingSprings, or
//           Alias (another view of its binding's memory: a second declaration at that binding,
//           which costs no descriptor; no kernel uses both names of one buffer),
//   keep:   Scratch (rewritten by the kernels), State (the host keeps a copy between batches, and
//           state files hold it after the File rows, in table order, for restarts), File (kept,
//           and written to state files in table order), Constant (uploaded once; the parts'
//           rows also hold what each rebuild finds, BodyPart),
//           Walls (every wall's row once, the moving walls' rows every batch: walls.h wall_at).
// Aliases: old_partner and old_history live only from save_old_contacts to contact_fill of a
// rebuild, candidates from contact_count to contact_fill; trans_list (transpose_fill),
// contact_force and torque_i (the contact kernel) are rewritten after that in the same step;
// scan_blocks (on torque_j's binding) only within one scan of a rebuild, before the contact kernel
// rewrites torque_j; touches lives from clear_touches to the contact kernel of a step, cell_of only from
// bucket_count to bucket_scatter of a rebuild before it, cell_fill only in its bucket_scatter
// before.
// Particles sit in storage slots in any order (host/engine/particle_order.h: cell order, for
// locality); each has a global id, its place in the case, which the host's state and every output
// use. Every order that reaches a float result goes by global id (B_ids), never by slot, so the
// bytes do not depend on the storage order (docs/engineering.md, particle order).
// The rolling springs hold contact c's EPSD spring at [c] and, during a rebuild, the old list's
// at [capacity + c] (one binding, not two: the per-stage limit on lavapipe is 32 buffers, and the
// table now binds 32: a new buffer must be an alias of one whose life it does not overlap).
#define REPOSE_BUFFERS(X) \
  X(0, Pos, pos, vec4, Particles, Always, File)               /* xyz position, w radius */ \
  X(1, Vel, vel, vec4, Particles, Always, File)               /* xyz velocity, w 1/mass */ \
  X(2, Omega, omega, vec4, Particles, Always, File)           /* xyz angular velocity, w 1/I */ \
  X(3, Force, force, vec4, Particles, Always, File)           /* xyz contact force sum */ \
  X(4, Torque, torque, vec4, Particles, Always, File)         /* xyz contact torque sum */ \
  X(5, Control, control, uint, Control, Always, State)        /* kCtl* words */ \
  X(6, Material, material, uint, Particles, Always, Constant) \
  X(7, Pairs, pairs, PairParams, Pairs, Always, Constant)     /* per material pair */ \
  X(8, Walls, walls, WallState, WallRows, Always, Walls)      /* every wall, then the moving ones at each step of a batch */ \
  X(9, PosAtBuild, pos_at_build, vec4, Particles, Always, State)  /* position at the list's build */ \
  X(10, CellOf, cell_of, uint, Particles, Always, Scratch)    /* hash bucket of each particle */ \
  X(11, CellStart, cell_start, uint, BucketsPlusOne, Always, Scratch)  /* counts, scanned to starts */ \
  X(12, CellFill, cell_fill, uint, Buckets, Always, Scratch)  /* scatter cursor */ \
  X(13, Sorted, sorted, uint, Particles, Always, Scratch)     /* slots by bucket, by global id within one */ \
  X(14, RowStart, row_start, uint, ParticlesPlusOne, Always, File)  /* contacts per owner, scanned (CSR) */ \
  X(15, Partner, partner, uint, Contacts, Always, File)       /* slot j (global id above i's), or N + w for wall w */ \
  X(16, Owner, owner, uint, Contacts, Always, State)          /* i */ \
  X(17, History, history, vec4, Contacts, Always, File)       /* xyz tangential spring, w age (steps) */ \
  X(18, OldRowStart, old_row_start, uint, ParticlesPlusOne, Always, Scratch)  /* the list before a rebuild */ \
  X(19, ContactForce, contact_force, vec4, Contacts, Always, Scratch)  /* force on the owner i */ \
  X(20, TorqueI, torque_i, vec4, Contacts, Always, Scratch)   /* torque on i */ \
  X(21, TorqueJ, torque_j, vec4, Contacts, FullEntries, Scratch)  /* torque on j */ \
  X(22, TransStart, trans_start, uint, ParticlesPlusOne, Always, State)  /* contacts as the partner (CSR) */ \
  X(23, TransFill, trans_fill, uint, Particles, Always, Scratch)  \
  X(24, TransList, trans_list, uint, Transposed, Always, State)  /* contact indices, by the owner's global id per row */ \
  X(25, WallForce, wall_force, vec4, WallSums, Always, Scratch)  /* force on each named wall, its sum, its peak */ \
  X(26, Bodies, bodies, Body, Bodies, Bodies, File)           /* rigid bodies (clumps) */ \
  X(27, Subs, subs, SubSphere, Particles, Bodies, Constant)   /* each particle's body and offset */ \
  X(28, RollingSpring, rolling_spring, vec4, ContactsTwice, RollingSprings, File)  /* EPSD springs */ \
  X(29, Ids, ids, uint, ParticlesTwice, Always, Constant)    /* [i] slot i's global id, [N + g] id g's slot */ \
  X(30, Parts, parts, BodyPart, Parts, Bodies, Constant)     /* the bodies' parts, for the broad phase */ \
  X(31, WallGrid, wall_grid, uint, WallGrid, Always, Constant)  /* walls by grid cell (kernels/neighbour.h walk_walls) */ \
  X(24, OldPartner, old_partner, uint, Contacts, Alias, Scratch)  /* the old list's partners */ \
  X(21, ScanBlocks, scan_blocks, uint, ScanBlocks, Alias, Scratch)  /* a scan's block sums (scan.comp): torque_j is dead during a rebuild */ \
  X(19, OldHistory, old_history, vec4, Contacts, Alias, Scratch)  /* the old list's histories */ \
  X(20, Candidates, candidates, uint, CandidateSlots, Alias, Scratch)  /* what contact_count found */ \
  X(10, Touches, touches, uint, Particles, Alias, Scratch)   /* touching contacts per body (spinning friction) */

// Neighbour candidates of one particle that contact_count keeps for contact_fill (more: it walks
// again). They share torque_i's binding, whose memory is the larger of the two views
// (binding_bytes), so any list capacity has room for them.
REPOSE_CONST kCandidateSlots = 16u;
// Parts of other bodies whose bounding spheres meet a part's that it can list (BodyPart::near).
REPOSE_CONST kPartNearSlots = 15u;
// bucket_count's bucket for a sub-sphere that meets no other body (neighbour.h): none.
REPOSE_CONST kNoBucket = 0xffffffffu;

#define REPOSE_BINDING_CONSTANT(binding, Name, name, type, count, need, keep) REPOSE_CONST kBind##Name = binding;
#define REPOSE_BINDING_COUNT(binding, Name, name, type, count, need, keep) REPOSE_COUNT_##need
#define REPOSE_COUNT_Always +1u
#define REPOSE_COUNT_FullEntries +1u
#define REPOSE_COUNT_Bodies +1u
#define REPOSE_COUNT_RollingSprings +1u
#define REPOSE_COUNT_Alias
REPOSE_BUFFERS(REPOSE_BINDING_CONSTANT)
// Descriptors: the rows that are not aliases. 32, lavapipe's limit of storage buffers per stage
// (host/vk/kernel_set.cpp refuses a device with fewer): a new buffer must be an alias.
REPOSE_CONST kBindingCount = 0u REPOSE_BUFFERS(REPOSE_BINDING_COUNT);
#undef REPOSE_BINDING_CONSTANT
#undef REPOSE_BINDING_COUNT

// ---- Control words: flags and indirect-dispatch arguments written on the device. ----
REPOSE_CONST kCtlNeedRebuild = 0;    // set by the skin check, read by rebuild_args
REPOSE_CONST kCtlRebuilding = 1;     // 1 during a step that rebuilds the list
REPOSE_CONST kCtlOverflow = 2;       // contact list exceeded its capacity (batch is redone)
REPOSE_CONST kCtlContacts = 3;       // contacts in the current list
REPOSE_CONST kCtlStepsSinceBuild = 4;
REPOSE_CONST kCtlRebuildCount = 5;
REPOSE_CONST kCtlMaxContacts = 6;    // the largest list needed so far
REPOSE_CONST kCtlOldContacts = 7;    // contacts in the list being replaced
REPOSE_CONST kCtlArgsParticles = 8;  // 3 words: x,y,z groups over N (0 when not rebuilding)
REPOSE_CONST kCtlArgsBuckets = 11;   // 3 words: groups over T+1 buckets
REPOSE_CONST kCtlArgsOne = 14;       // 3 words: one group (scans)
REPOSE_CONST kCtlArgsOldContacts = 17;  // 3 words: groups over the old list
REPOSE_CONST kCtlArgsContacts = 20;  // 3 words: groups over the current list (every step)
REPOSE_CONST kCtlArgsNewContacts = 23;  // 3 words: the same, only in a step that rebuilds
REPOSE_CONST kCtlArgsParts = 26;     // 3 words: groups over the bodies' parts (0 when not rebuilding)
REPOSE_CONST kCtlArgsBodies = 29;    // 3 words: groups over the bodies (0 when not rebuilding)
REPOSE_CONST kCtlArgsScanBuckets = 32;    // 3 words: a scan's blocks over T+1 buckets (0 when not rebuilding)
REPOSE_CONST kCtlArgsScanParticles = 35;  // 3 words: a scan's blocks over N particles (0 when not rebuilding)
REPOSE_CONST kControlWords = 38;

// ---- Option bits (SimPush::flags). Defaults (all zero) are EDEM's. ----
REPOSE_CONST kFlagCoulombSpringOnly = 1u;     // LIGGGHTS: cap the spring, drop damping while sliding
REPOSE_CONST kFlagClipAttraction = 2u;        // clip the attractive end-of-contact normal force
REPOSE_CONST kFlagRollingConstTorque = 4u;    // EDEM standard rolling friction (CDT)
REPOSE_CONST kFlagRollingRelativeOmega = 8u;  // LIGGGHTS cdt: relative instead of own omega
REPOSE_CONST kFlagDrift = 16u;                // kick kernels: also move positions and check the skin
REPOSE_CONST kFlagKeepHistory = 32u;          // forces without updating springs (setup, as LIGGGHTS)
REPOSE_CONST kFlagLeanContacts = 64u;         // contact kernels store the lean entry (contacts.h)
REPOSE_CONST kFlagBodies = 128u;              // particles are sub-spheres of rigid bodies (bodies.h)
REPOSE_CONST kFlagRollingSpring = 256u;       // EDEM type C (EPSD) rolling resistance, full entries only
REPOSE_CONST kFlagSpinningFriction = 512u;    // some pair has spinning friction (PairParams::spinning_friction), full entries only
REPOSE_CONST kFlagCohesionContactFriction = 1024u;  // Coulomb cap and rolling lever on the force before cohesion
REPOSE_CONST kFlagRollingLeverSphere = 2048u; // LIGGGHTS multisphere: a clump's rolling lever is the sub-sphere's
                                              // radius, not |contact point - centre of mass| (EDEM)
REPOSE_CONST kFlagCohesionIntersection = 4096u;  // LIGGGHTS sjkr: cohesion on the spheres' intersection disc
REPOSE_CONST kFlagBodyBroadPhase = 8192u;     // clumps: parts of bodies culled by bounding spheres first (neighbour.h part_near)
// The options that keep each contact's torques in its entry (per-contact springs, counts of
// contacts): they need full contact entries, never lean ones, and the SIMD lanes leave them to the
// scalar contact kernel. The one rule for both (step_program.cpp, contact_lanes.cpp).
REPOSE_CONST kFlagsNeedFullEntries = kFlagRollingSpring | kFlagSpinningFriction;

// ---- Scan selector (ScanPush::target) and passes (ScanPush::pass; shaders/scan.comp). ----
REPOSE_CONST kScanCells = 0;
REPOSE_CONST kScanRows = 1;
REPOSE_CONST kScanTransposed = 2;
REPOSE_CONST kScanBlockSums = 3;     // B_scan_blocks: the block sums, scanned by kScanPassOffsets
REPOSE_CONST kScanPassWhole = 0;     // one workgroup scans the whole array, a block at a time
REPOSE_CONST kScanPassSums = 1;      // workgroup b sums block b into B_scan_blocks[b]
REPOSE_CONST kScanPassOffsets = 2;   // one workgroup scans the block sums; the total lands at [count]
REPOSE_CONST kScanPassBlocks = 3;    // workgroup b scans block b from its offset B_scan_blocks[b]

REPOSE_CONST kWallPlane = 0;
REPOSE_CONST kWallCylinder = 1;
REPOSE_CONST kWallRectangle = 2;
REPOSE_CONST kWallTriangle = 3;
// Which part of a rectangle or triangle is closest to a sphere (walls.h).
REPOSE_CONST kFeatureFace = 0;
REPOSE_CONST kFeatureEdge = 1;
REPOSE_CONST kFeatureVertex = 2;
// Two triangles of a mesh are coplanar (one flat patch) when |n1 . n2| reaches this (0.26 deg).
// Spinning friction leaves relative spins below this (rad/s) alone, and rolling torques the
// spin's components below it (contact_law.h): spinning friction's limiter halves a spin each step,
// and a rolling torque shrinks a small component of a stopped roll step after step, either of
// which would walk it into the denormal range that some GPUs flush.
#ifdef __cplusplus
inline constexpr float kCoplanarCos = 0.99999f;
inline constexpr float kSpinFloor = 1e-20f;
#else
const float kCoplanarCos = 0.99999f;
const float kSpinFloor = 1e-20f;
#endif

REPOSE_CONST kDefaultWorkgroup = 64;
REPOSE_CONST kScanWorkgroup = 256;      // threads of a scan's workgroup
REPOSE_CONST kScanPerThread = 8;        // entries each of them scans
REPOSE_CONST kScanBlock = kScanWorkgroup * kScanPerThread;  // entries of a scan's block
REPOSE_CONST kWallReduceWorkgroup = 256;

// ---- Contact parameters of a material pair: one table, one row per float of PairParams. ----
// The host computes them in double and rounds each once (pair_params, host/engine/model.cpp); the
// contact law reads them by name on every backend (pp.rolling_friction in kernels/contact_law.h);
// the SIMD lanes gather each row at its word (kernels_ref/contact_lanes.cpp). A row's slot is its
// place in the table: word k of PairParams. Adding a per-pair constant is a row here and, by its
// source, either the Interaction field of that name with its case key (interaction) or a member
// of the same name in DerivedPairConstants, with its formula (derived; model.cpp). Columns:
//   name, unit (1: dimensionless; tests draw values by it), source: interaction or derived.
#define REPOSE_PAIR_PARAMS(X) \
  X(e_star, Pa, derived)                /* E*: 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b */ \
  X(g_star, Pa, derived)                /* G*: 1/G* = 2 (2 - nu_a)(1 + nu_a)/E_a + the same for b */ \
  X(damping, 1, derived)                /* -2 sqrt(5/6) beta >= 0, beta from the restitution */ \
  X(static_friction, 1, interaction)    /* mu_s: |Ft| <= mu_s |Fn| */ \
  X(rolling_friction, 1, interaction)   /* mu_r: rolling torque mu_r |Fn| R, the EPSD spring's cap */ \
  X(viscoelastic_time, s, interaction)  /* A, extension restitution_velocity (0: off) */ \
  X(cohesion_pi_k, J/m^3, derived)      /* pi x cohesion_energy_density, extension cohesion (0: off) */ \
  X(spinning_friction, 1, interaction)  /* mu_spin (0: off) */ \
  X(tangential_damping, 1, interaction) /* 1: the tangential dashpot on (EDEM), 0: off (LIGGGHTS) */

struct PairParams {
#define REPOSE_PAIR_FIELD(name, unit, source) float name;
  REPOSE_PAIR_PARAMS(REPOSE_PAIR_FIELD)
#undef REPOSE_PAIR_FIELD
};
#define REPOSE_PAIR_COUNT(name, unit, source) +1u
REPOSE_CONST kPairParamCount = 0u REPOSE_PAIR_PARAMS(REPOSE_PAIR_COUNT);
#undef REPOSE_PAIR_COUNT

// One wall at one step of a batch; the host evaluates prescribed motion.
struct WallState {
  vec4 p0;     // plane: point;  cylinder: base centre;  rectangle: centre;  triangle: vertex a
  vec4 p1;     // plane, rectangle: unit normal into the domain; cylinder: unit axis, w radius;
               // triangle: vertex b
  vec4 vel;    // xyz translational velocity, w cylinder height
  vec4 omega;  // xyz angular velocity about `centre`
  vec4 centre; // xyz a point on the rotation axis
  uvec4 info;  // x type, y material, z mesh id (triangles), w the named wall it belongs to (wall_reduce)
  vec4 p2;     // rectangle: unit in-plane axis u, w half extent along u;  triangle: vertex c
  vec4 p3;     // rectangle: unit axis v, w half extent along v;  triangle: unit normal
  uvec4 topo;  // triangle: the mesh's vertex ids of a, b, c (shared corners, walls.h); w 0 for a
               // wall that never moves, else 1 + its place among the moving walls (walls.h wall_at)
};

// A rigid body (a clump of sub-spheres; with kFlagBodies a lone sphere is a one-sphere body).
// The body frame is the principal frame, so the inertia tensor there is diagonal. Angular
// momentum is the integrated quantity: a torque-free body keeps it to the bit.
struct Body {
  vec4 pos;          // xyz centre of mass, w 1/mass
  vec4 vel;          // xyz velocity of the centre of mass
  vec4 quat;         // orientation (x, y, z, w): body frame -> world
  vec4 ang_mom;      // xyz angular momentum about the centre of mass, world frame
  vec4 omega;        // xyz angular velocity, world frame (follows from quat and ang_mom)
  vec4 inv_inertia;  // xyz 1 / principal moments of inertia
  vec4 force;        // xyz sum of the sub-spheres' contact forces (no gravity)
  vec4 torque;       // xyz torque about the centre of mass
  uvec4 spheres;     // x first sub-sphere's global id, y count (a body's sub-spheres have consecutive ids)
  vec4 drag;         // xyz silhouette area / pi seen along each principal axis (m^2; a sphere:
                     // r^2), for air drag; zero when the case has no air drag
};

// What a particle needs to know of its body; static during a run.
struct SubSphere {
  vec4 local;  // xyz centre in the body frame, w radius
  uvec4 info;  // x body index, y its body's first part, z its own part (BodyPart index), w unused
};

// A part of a body for the broad phase (neighbour.h part_near): a slab of its sub-spheres across
// the body's longest axis, so a long body is culled by a few small spheres, not one large one.
// A body's parts are consecutive, in body order. `local` and `info` are static during a run;
// each rebuild writes the rest (uploaded as zeros).
struct BodyPart {
  vec4 local;  // xyz centre in the body frame, w radius of a sphere about it holding its sub-spheres
  uvec4 info;  // x body index, y the body's parts, z the body's bounding radius about its centre
               // of mass (float bits); w the walls its sphere may meet (part_near, each rebuild)
  vec4 world;  // part_place: xyz the centre where the body is now, w the radius
  uint near_count;             // part_near: parts of other bodies whose spheres meet this one's,
  uint near[kPartNearSlots];   // the first of them by index (more than kPartNearSlots: none kept)
};

// Push constants of the simulation kernels (<= 128 bytes, lavapipe's limit).
struct SimPush {
  uint n_particles;
  uint n_walls;
  uint capacity;       // contact list capacity
  uint table_size;     // hash buckets T (power of two)
  uint n_materials;
  uint flags;
  uint wall_slot;      // which WallState row of the batch
  uint max_interval;   // rebuild at least every this many steps (0: only on the skin check)
  uint workgroup;      // the kernels' workgroup size, for indirect argument computation
  float dt;
  float kick;          // fraction of dt for velocity kicks (0.5 velocity Verlet, 1 symplectic Euler)
  float gx;
  float gy;
  float gz;
  float inv_cell;      // 1 / hash cell edge
  float skin;
  float half_skin_sq;  // (skin/2)^2: a particle moved this far (squared) forces a rebuild
  uint n_bodies;       // rigid bodies (0 without kFlagBodies)
  float large_radius;  // particles above this radius go to the large bucket (neighbour.h)
  float air_drag;      // extension air_drag: 0.5 rho_air C_d pi (x r^2 = drag per v^2), 0: off
  float rolling_damping;  // kFlagRollingSpring: eta_r, the rolling dashpot's fraction of critical
  uint absent_wall_kinds;  // bit k: no wall of kind k in the run (0: any may be present)
  uint max_groups_x;  // workgroups per dispatch row: more go into rows along y (dispatch_rows)
  uint wall_sums;     // wall_reduce: 0 the force only; 1 also its sum and peak; 2 those anew
  uint n_parts;       // the bodies' parts (BodyPart rows; 0 without kFlagBodies)
  uint n_moving_walls;   // walls with a prescribed motion: a row each per step of the batch (wall_at)
  uint wall_table_size;  // buckets of the wall grid (neighbour.h walk_walls); 0: every sphere tests every wall
  uint n_wall_groups;    // named walls (a mesh's triangles are one): wall_reduce's sums
};

struct ScanPush {
  uint target;  // kScanCells, kScanRows, kScanTransposed
  uint count;   // entries to scan (the total lands at [count])
  uint pass;    // kScanPassWhole, or kScanPassSums, kScanPassOffsets, kScanPassBlocks in turn
};

// Vulkan guarantees 65,535 workgroups along x (maxComputeWorkGroupCount[0]); some GPUs allow no
// more. A dispatch of more groups runs as rows of at most max_groups_x along y; every kernel takes
// its index from invocation_index() (kernels/glsl_prelude.glsl), which counts across the rows.
REPOSE_CONST kMaxGroupsX = 65535u;

// How the kernels round a division and a square root (div_rn and sqrt_rn in
// kernels/glsl_prelude.glsl, a specialisation constant chosen by host/vk/kernel_set.cpp):
// as the device does (lavapipe and the CPU twin round both correctly), corrected to the correctly
// rounded result (hardware GPUs: Vulkan allows 2.5 ULP for a division), or, for tests, first put
// up to 2 ULP off and then corrected, so that lavapipe exercises the correction.
REPOSE_CONST kRoundingDevice = 0u;
REPOSE_CONST kRoundingCorrected = 1u;
REPOSE_CONST kRoundingTest = 2u;
#ifdef __cplusplus
inline uint dispatch_rows(uint groups, uint max_x) { return groups == 0u ? 1u : (groups + max_x - 1u) / max_x; }
inline uint dispatch_columns(uint groups, uint max_x) { return groups < max_x ? groups : max_x; }
#else
uint dispatch_rows(uint groups, uint max_x) { return groups == 0u ? 1u : (groups + max_x - 1u) / max_x; }
uint dispatch_columns(uint groups, uint max_x) { return groups < max_x ? groups : max_x; }
#endif
// The blocks of kScanBlock entries that a scan of `count` entries takes, a workgroup each.
#ifdef __cplusplus
inline uint scan_blocks_for(uint count) { return (count + kScanBlock - 1u) / kScanBlock; }
#else
uint scan_blocks_for(uint count) { return (count + kScanBlock - 1u) / kScanBlock; }
#endif

#ifdef __cplusplus
static_assert(sizeof(PairParams) == 4 * kPairParamCount, "PairParams holds floats only: the lanes gather its words");
static_assert(sizeof(WallState) == 144);
static_assert(sizeof(Body) == 160);
static_assert(sizeof(SubSphere) == 32);
static_assert(sizeof(BodyPart) == 112, "std430: a vec4-aligned struct, its uint array packed");
static_assert(sizeof(SimPush) <= 128, "push constants above lavapipe's 128 B");
static_assert(sizeof(ScanPush) <= 128);
}  // namespace repose::gpu
#endif

#endif
