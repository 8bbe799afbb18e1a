#include "engine/model.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "case/body_pose.h"
#include "case/time_step.h"
#include "engine/wall_grid.h"
#include "geometry/clump.h"
#include "geometry/projected_area.h"
#include "util/math.h"

namespace repose {

namespace {

gpu::vec4 v4(Vec3d a, double w) {
  return gpu::vec4(float(a[0]), float(a[1]), float(a[2]), float(w));
}

gpu::vec4 v4(const Quat& q) {  // (w, x, y, z) -> the kernels' (x, y, z, w)
  return gpu::vec4(float(q[1]), float(q[2]), float(q[3]), float(q[0]));
}

uint32_t next_pow2(uint32_t v) {
  uint32_t p = 1;
  while (p < v) p <<= 1;
  return p;
}

// Particles above half the largest radius skip the hash grid when they are few (at most
// max(64, N/32)): the cell then fits the small ones (a cabbage's veins, not its core).
void choose_large_radius(Model& m, double& r_cell) {
  double r_max = 0;
  for (const auto& p : m.pos) r_max = std::max(r_max, double(p.w));
  double split = 0;
  size_t large = 0;
  for (const auto& p : m.pos) {
    if (double(p.w) <= 0.5 * r_max) split = std::max(split, double(p.w));
    else ++large;
  }
  if (large == 0 || split == 0 || large > std::max<size_t>(64, m.pos.size() / 32)) return;
  m.large_radius = split;
  r_cell = split;
}

// Mass properties of a template at density 1 and scale 1, in its principal frame.
struct TemplateFrame {
  MassProperties unit;      // density 1: mass = volume
  Quat principal;           // principal frame -> template frame
  std::vector<Vec3d> local; // sub-sphere centres in the principal frame, about the centre of mass
  Vec3d silhouette{};       // projected areas along the principal axes (with air drag only)
};

TemplateFrame template_frame(const TemplateSpec& t, bool silhouette) {
  TemplateFrame f;
  f.unit = compute_mass_properties(t.clump, 1.0);
  const glm::dmat3& a = f.unit.principal_axes;
  f.principal = quat_from_columns({a[0][0], a[0][1], a[0][2]}, {a[1][0], a[1][1], a[1][2]},
                                  {a[2][0], a[2][1], a[2][2]});
  for (const Sphere& s : t.clump.spheres) {
    glm::dvec3 d = s.centre - f.unit.centre_of_mass;
    f.local.push_back({glm::dot(a[0], d), glm::dot(a[1], d), glm::dot(a[2], d)});
  }
  if (silhouette) {
    std::vector<double> radii;
    for (const Sphere& s : t.clump.spheres) radii.push_back(s.radius);
    f.silhouette = projected_areas(f.local, radii);
  }
  return f;
}

// The parts of a body for the broad phase (neighbour.h part_near): slabs across the longest axis
// of its sub-spheres' box (in the body frame), about twice as many as the box is longer than
// wide, so a part is half as long as the body is wide (the cotton-stalk study's 10 x 80 mm stalk:
// 16 parts of ~5.6 mm radius; at rest in the bucket 12 % of its sub-spheres then walk the grid
// against 25 % with 8 parts; docs/engineering.md). Each slab that holds a sub-sphere is a part,
// centred in its sub-spheres' box, its radius rounded outwards and widened by 1e-5 of the body's
// bounding radius: the float rotations of body_place and part_place err by far less. Sets each
// sub-sphere's part (info.z) and its body's first (info.y) from `first_sub` on. `bound`: the body's bounding radius about its
// centre of mass, rounded outwards here (1e-5 of it covers body_place's roundings likewise).
void add_body_parts(const std::vector<Vec3d>& local, const std::vector<double>& radii, double bound, uint32_t body,
                    uint32_t first_sub, Model& m) {
  Vec3d lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t k = 0; k < local.size(); ++k)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], local[k][a] - radii[k]);
      hi[a] = std::max(hi[a], local[k][a] + radii[k]);
    }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  double across = 0;
  for (int a = 0; a < 3; ++a)
    if (a != axis) across = std::max(across, hi[a] - lo[a]);
  double length = hi[axis] - lo[axis];
  int slabs = across > 0 ? int(std::clamp(std::floor(2 * length / across), 1.0, 64.0)) : 1;
  std::vector<int> slab(local.size());
  for (size_t k = 0; k < local.size(); ++k)
    slab[k] = std::min(slabs - 1, int(std::floor((local[k][axis] - lo[axis]) / length * slabs)));
  uint32_t first_part = static_cast<uint32_t>(m.parts.size());
  for (int sl = 0; sl < slabs; ++sl) {
    Vec3d box_lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, box_hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t k = 0; k < local.size(); ++k)
      if (slab[k] == sl)
        for (int a = 0; a < 3; ++a) {
          box_lo[a] = std::min(box_lo[a], local[k][a]);
          box_hi[a] = std::max(box_hi[a], local[k][a]);
        }
    if (box_lo[0] > box_hi[0]) continue;  // an empty slab
    Vec3d centre = mul(add(box_lo, box_hi), 0.5);
    double radius = 0;
    for (size_t k = 0; k < local.size(); ++k) {
      if (slab[k] != sl) continue;
      Vec3d d = sub(local[k], centre);
      radius = std::max(radius, std::sqrt(dot(d, d)) + radii[k]);
      m.subs[first_sub + k].info.y = first_part;
      m.subs[first_sub + k].info.z = static_cast<uint32_t>(m.parts.size());
    }
    gpu::BodyPart part{};
    part.local = v4(centre, radius * (1 + 1e-6) + 1e-5 * bound);
    part.info = gpu::uvec4(body, 0u, std::bit_cast<uint32_t>(float(bound * (1 + 1e-5))), 0u);
    m.parts.push_back(part);
  }
  for (size_t p = first_part; p < m.parts.size(); ++p) m.parts[p].info.y = uint32_t(m.parts.size() - first_part);
}

// Every particle becomes a sub-sphere of a body: lone spheres first (one-sphere bodies), then
// the case's bodies in order, each body's sub-spheres contiguous.
void add_bodies(const CaseSpec& spec, Model& m) {
  bool drag = spec.air_drag.drag_coefficient > 0;
  auto push_body = [&](Vec3d centre, double mass, Quat q, Vec3d moments, Vec3d v, Vec3d w,
                       const std::vector<Vec3d>& local, const std::vector<double>& radii,
                       uint32_t material, Vec3d drag_area, bool fixed) {
    gpu::Body b{};
    uint32_t first = static_cast<uint32_t>(m.subs.size());
    // A fixed body has infinite mass and inertia: 1/mass = 0 marks it for the kernels.
    double inv_mass = fixed ? 0.0 : 1.0 / mass;
    b.pos = v4(centre, inv_mass);
    b.vel = v4(v, 0);
    b.quat = v4(q);
    Quat conj{q[0], -q[1], -q[2], -q[3]};
    Vec3d wb = rotate(conj, w);
    Vec3d lb{moments[0] * wb[0], moments[1] * wb[1], moments[2] * wb[2]};
    b.ang_mom = v4(rotate(q, lb), 0);
    b.omega = v4(w, 0);
    b.inv_inertia = fixed ? v4({0, 0, 0}, 0) : v4({1 / moments[0], 1 / moments[1], 1 / moments[2]}, 0);
    b.spheres = gpu::uvec4(first, uint32_t(local.size()), 0u, 0u);
    b.drag = v4(mul(drag_area, 1 / kPi), 0);
    // The bounding radius about the centre of mass (neighbour.h part_near).
    double bound = 0;
    for (size_t k = 0; k < local.size(); ++k) bound = std::max(bound, std::sqrt(dot(local[k], local[k])) + radii[k]);
    for (size_t k = 0; k < local.size(); ++k) {
      gpu::SubSphere s{};
      s.local = v4(local[k], radii[k]);
      s.info = gpu::uvec4(uint32_t(m.bodies.size()), 0u, 0u, 0u);
      m.subs.push_back(s);
      Vec3d r = rotate(q, local[k]);
      m.pos.push_back(v4(add(centre, r), radii[k]));
      m.vel.push_back(v4(add(v, cross(w, r)), inv_mass));
      m.omega.push_back(v4(w, 0));
      m.material.push_back(material);
    }
    add_body_parts(local, radii, bound, uint32_t(m.bodies.size()), first, m);
    if (!fixed) m.total_mass += mass;
    m.bodies.push_back(b);
  };
  for (const SphereSpec& s : spec.spheres) {
    const Material& mat = spec.materials.at(size_t(s.material));
    double mass = mat.density * 4.0 / 3.0 * kPi * s.radius * s.radius * s.radius;
    double inertia = 0.4 * mass * s.radius * s.radius;
    double area = drag ? kPi * s.radius * s.radius : 0;
    push_body(s.position, mass, {1, 0, 0, 0}, {inertia, inertia, inertia}, s.velocity,
              s.angular_velocity, {{0, 0, 0}}, {s.radius}, uint32_t(s.material), {area, area, area}, s.fixed);
  }
  std::vector<std::optional<TemplateFrame>> frames(spec.templates.size());
  for (const BodySpec& body : spec.bodies) {
    const TemplateSpec& t = spec.templates.at(size_t(body.template_index));
    auto& frame = frames[size_t(body.template_index)];
    if (!frame) frame = template_frame(t, drag);
    double s = body.scale;
    double density = t.mass ? *t.mass / frame->unit.volume
                            : spec.materials.at(size_t(body.material)).density;
    double mass = density * frame->unit.volume * s * s * s;
    double s5 = density * s * s * s * s * s;
    Vec3d moments = mul({frame->unit.principal_moments.x, frame->unit.principal_moments.y,
                         frame->unit.principal_moments.z}, s5);
    glm::dvec3 com = frame->unit.centre_of_mass * s;
    Vec3d centre = add(body.position, rotate(body.orientation, {com.x, com.y, com.z}));
    Quat q = multiply(body.orientation, frame->principal);
    std::vector<Vec3d> local;
    std::vector<double> radii;
    for (size_t k = 0; k < frame->local.size(); ++k) {
      local.push_back(mul(frame->local[k], s));
      radii.push_back(t.clump.spheres[k].radius * s);
    }
    Vec3d area = mul(frame->silhouette, s * s);
    if (!drag) area = {0, 0, 0};
    push_body(centre, mass, q, moments, body.velocity, body.angular_velocity, local, radii,
              uint32_t(body.material), area, body.fixed);
  }
  m.n_particles = static_cast<uint32_t>(m.subs.size());
}

}  // namespace

bool needs_spinning_friction(const CaseSpec& spec) {
  return std::any_of(spec.interactions.begin(), spec.interactions.end(),
                     [](const Interaction& in) { return in.spinning_friction > 0; });
}

DerivedPairConstants derived_pair_constants(const Material& a, const Material& b, const Interaction& in) {
  auto youngs = [](const Material& m) {
    return m.youngs_modulus > 0 ? m.youngs_modulus : 2 * m.shear_modulus * (1 + m.poisson);
  };
  double ea = youngs(a), eb = youngs(b), na = a.poisson, nb = b.poisson;
  DerivedPairConstants d;
  d.e_star = 1.0 / ((1 - na * na) / ea + (1 - nb * nb) / eb);
  d.g_star = 1.0 / (2 * (2 - na) * (1 + na) / ea + 2 * (2 - nb) * (1 + nb) / eb);
  double ln_e = std::log(in.restitution);
  double beta = ln_e / std::sqrt(ln_e * ln_e + kPi * kPi);
  d.damping = -2.0 * std::sqrt(5.0 / 6.0) * beta;
  d.cohesion_pi_k = kPi * in.cohesion_energy_density;
  return d;
}

gpu::PairParams pair_params(const Material& a, const Material& b, const Interaction& in) {
  DerivedPairConstants derived = derived_pair_constants(a, b, in);
  gpu::PairParams p;
  // Every row of REPOSE_PAIR_PARAMS (shaders/repose_shared.h), from where its source column says.
#define REPOSE_PAIR_FROM_interaction(name) in.name
#define REPOSE_PAIR_FROM_derived(name) derived.name
#define REPOSE_PAIR_SET(name, unit, source) p.name = float(REPOSE_PAIR_FROM_##source(name));
  REPOSE_PAIR_PARAMS(REPOSE_PAIR_SET)
#undef REPOSE_PAIR_SET
#undef REPOSE_PAIR_FROM_derived
#undef REPOSE_PAIR_FROM_interaction
  return p;
}

gpu::WallState Model::wall_state(size_t w, double t) const {
  const ModelWall& mw = walls[w];
  const WallMotion& m = mw.motion;
  double active = std::clamp(t - m.start_time, 0.0, std::max(0.0, m.stop_time - m.start_time));
  bool moving = t >= m.start_time && t < m.stop_time;
  Vec3d shift = mul(m.velocity, active);
  Vec3d axis = dot(m.rotation_axis, m.rotation_axis) > 0 ? unit(m.rotation_axis) : Vec3d{0, 0, 1};
  double angle = m.angular_rate * active;
  Vec3d centre = add(m.rotation_axis_point, shift);
  auto point = [&](Vec3d p) { return add(centre, rotate_about(sub(p, m.rotation_axis_point), axis, angle)); };
  auto direction = [&](Vec3d d) { return rotate_about(d, axis, angle); };
  bool triangle = mw.kind == gpu::kWallTriangle;
  gpu::WallState s;
  s.p0 = v4(point(mw.p0), 0);
  s.p1 = v4(triangle ? point(mw.p1) : direction(mw.p1), mw.kind == gpu::kWallCylinder ? mw.radius : 0.0);
  s.vel = v4(moving ? m.velocity : Vec3d{0, 0, 0}, mw.height);
  s.omega = v4(moving ? mul(axis, m.angular_rate) : Vec3d{0, 0, 0}, 0);
  s.centre = v4(centre, 0);
  s.info = gpu::uvec4(mw.kind, mw.material, mw.mesh_id, mw.group);
  s.p2 = v4(triangle ? point(mw.p2) : direction(mw.p2), mw.half_u);
  s.p3 = v4(direction(mw.p3), mw.half_v);
  s.topo = gpu::uvec4(mw.vertex_ids[0], mw.vertex_ids[1], mw.vertex_ids[2], mw.moving_row);
  return s;
}

bool has_motion(const WallMotion& m) {
  return m.velocity[0] != 0 || m.velocity[1] != 0 || m.velocity[2] != 0 || m.angular_rate != 0;
}

std::vector<size_t> Model::wall_groups() const {
  std::vector<size_t> group;
  std::vector<std::string> names;
  for (const auto& w : walls) {
    // Mesh triangles share their wall's name; box faces keep their own (base.xmin ...).
    auto it = std::find(names.begin(), names.end(), w.name);
    if (it == names.end()) {
      names.push_back(w.name);
      group.push_back(names.size() - 1);
    } else {
      group.push_back(size_t(it - names.begin()));
    }
  }
  return group;
}

std::vector<std::string> Model::wall_group_names() const {
  std::vector<std::string> names;
  for (const auto& w : walls)
    if (std::find(names.begin(), names.end(), w.name) == names.end()) names.push_back(w.name);
  return names;
}

namespace {

// Lone spheres (when the case has no bodies: with bodies they were added as one-sphere bodies).
void add_spheres(const CaseSpec& spec, Model& m) {
  for (const auto& s : spec.spheres) {
    const Material& mat = spec.materials.at(s.material);
    double mass = mat.density * 4.0 / 3.0 * kPi * s.radius * s.radius * s.radius;
    double inertia = 0.4 * mass * s.radius * s.radius;
    if (!s.fixed) m.total_mass += mass;
    m.pos.push_back(v4(s.position, s.radius));
    // A fixed sphere: 1/mass = 0 and 1/inertia = 0 (neighbour.h, integrate.h).
    m.vel.push_back(v4(s.velocity, s.fixed ? 0.0 : 1.0 / mass));
    m.omega.push_back(v4(s.angular_velocity, s.fixed ? 0.0 : 1.0 / inertia));
    m.material.push_back(static_cast<uint32_t>(s.material));
  }
}

// Pair table: the interaction entries, symmetric. Unused pairs keep zeros (never looked up:
// the loader refuses cases whose materials meet without an interaction).
void add_pairs(const CaseSpec& spec, Model& m) {
  m.pairs.assign(size_t(m.n_materials) * m.n_materials, gpu::PairParams{});
  for (const auto& in : spec.interactions) {
    auto p = pair_params(spec.materials[in.material_a], spec.materials[in.material_b], in);
    m.pairs[size_t(in.material_a) * m.n_materials + in.material_b] = p;
    m.pairs[size_t(in.material_b) * m.n_materials + in.material_a] = p;
  }
}

// The wall rows of [[wall]] number wi: a plane or rectangle is one row, a box up to six planes,
// a mesh one row per triangle.
void add_wall(const CaseSpec& spec, size_t wi, Model& m) {
  const WallSpec& w = spec.walls[wi];
  std::string base = w.name.empty() ? "wall" + std::to_string(wi) : w.name;
  // A wall row of this [[wall]]: kind, material, motion and names are shared by its rows.
  auto row = [&](uint32_t kind, const std::string& name) {
    ModelWall mw;
    mw.kind = kind;
    mw.material = static_cast<uint32_t>(w.material);
    mw.motion = w.motion;
    mw.name = name;
    mw.spec_index = static_cast<int>(wi);
    return mw;
  };
  auto plane = [&](Vec3d point, Vec3d normal, const std::string& name) {
    ModelWall mw = row(gpu::kWallPlane, name);
    mw.p0 = point;
    mw.p1 = unit(normal);
    m.walls.push_back(mw);
  };
  auto face = [&](Vec3d point, Vec3d normal, const std::string& suffix) {
    if (std::find(w.open_faces.begin(), w.open_faces.end(), suffix) == w.open_faces.end())
      plane(point, normal, base + "." + suffix);
  };
  switch (w.type) {
    case WallSpec::Type::Plane: plane(w.point, w.normal, base); break;
    case WallSpec::Type::Box: {
      // Six inward-facing planes (less the open ones); particles live inside.
      face(w.box_min, {1, 0, 0}, "xmin");
      face(w.box_max, {-1, 0, 0}, "xmax");
      face(w.box_min, {0, 1, 0}, "ymin");
      face(w.box_max, {0, -1, 0}, "ymax");
      face(w.box_min, {0, 0, 1}, "zmin");
      face(w.box_max, {0, 0, -1}, "zmax");
      break;
    }
    case WallSpec::Type::Rectangle: {
      ModelWall mw = row(gpu::kWallRectangle, base);
      mw.p0 = w.point;
      mw.p1 = unit(w.normal);
      mw.p2 = unit(sub(w.edge_axis, mul(mw.p1, dot(w.edge_axis, mw.p1))));
      mw.p3 = cross(mw.p1, mw.p2);
      mw.half_u = 0.5 * w.size[0];
      mw.half_v = 0.5 * w.size[1];
      m.walls.push_back(mw);
      break;
    }
    case WallSpec::Type::Mesh: {
      // One wall row per triangle; vertex ids let the kernels find shared corners.
      for (const auto& tri : w.mesh->triangles) {
        ModelWall mw = row(gpu::kWallTriangle, base);
        mw.p0 = w.mesh->vertices[tri[0]];
        mw.p1 = w.mesh->vertices[tri[1]];
        mw.p2 = w.mesh->vertices[tri[2]];
        mw.p3 = unit(cross(sub(mw.p1, mw.p0), sub(mw.p2, mw.p0)));
        mw.mesh_id = static_cast<uint32_t>(wi);
        mw.vertex_ids = tri;
        m.walls.push_back(mw);
      }
      break;
    }
    case WallSpec::Type::Cylinder: {
      ModelWall mw = row(gpu::kWallCylinder, base);
      mw.p0 = w.base;
      mw.p1 = unit(w.axis);
      mw.radius = w.radius;
      mw.height = w.height;
      m.walls.push_back(mw);
      break;
    }
  }
}

// The [contact] options and extensions as kernel flags (and the constants that go with them).
void set_contact_flags(const CaseSpec& spec, Model& m) {
  if (spec.contact.coulomb_cap == CoulombCap::SpringOnly) m.flags |= gpu::kFlagCoulombSpringOnly;
  if (spec.contact.normal_attraction == NormalAttraction::Clip) m.flags |= gpu::kFlagClipAttraction;
  if (spec.contact.cohesion_friction == CohesionFriction::Contact) m.flags |= gpu::kFlagCohesionContactFriction;
  if (spec.contact.rolling == RollingModel::ConstantTorque) m.flags |= gpu::kFlagRollingConstTorque;
  if (spec.contact.rolling_omega == RollingOmega::Relative) m.flags |= gpu::kFlagRollingRelativeOmega;
  if (spec.contact.rolling_lever == RollingLever::Sphere) m.flags |= gpu::kFlagRollingLeverSphere;
  if (spec.contact.cohesion_area == CohesionArea::Intersection) m.flags |= gpu::kFlagCohesionIntersection;
  if (spec.contact.rolling == RollingModel::ElasticPlastic) {
    m.flags |= gpu::kFlagRollingSpring;
    m.rolling_damping = spec.contact.rolling_damping;
  }
  if (needs_spinning_friction(spec)) m.flags |= gpu::kFlagSpinningFriction;
  if (spec.air_drag.drag_coefficient > 0)
    m.air_drag = 0.5 * spec.air_drag.air_density * spec.air_drag.drag_coefficient * kPi;
}

// The neighbour grid and rebuild policy, from the particles' radii and the walls' speeds.
void choose_neighbour_search(const CaseSpec& spec, Model& m) {
  // The radii as given for lone spheres, as stored (float) for the sub-spheres of bodies.
  double r_min = 1e300, r_max = 0;
  auto radius = [&](double r) {
    r_min = std::min(r_min, r);
    r_max = std::max(r_max, r);
  };
  if (spec.bodies.empty())
    for (const auto& s : spec.spheres) radius(s.radius);
  else
    for (const auto& p : m.pos) radius(double(p.w));
  // Skin: half the smallest radius by default, so a rebuild is needed only after a particle
  // moved a quarter of its radius. With clumps twice the smallest radius: their rebuilds cost far
  // more than the few candidates a wider skin adds (sub-spheres of one body never pair); the
  // cabbage cylinder heap takes 46 instead of 74 CPU-s. No result depends on the skin.
  double default_skin = (spec.bodies.empty() ? 0.5 : 2.0) * r_min;
  m.skin = spec.neighbour.skin >= 0 ? spec.neighbour.skin : default_skin;
  double r_cell = r_max;
  choose_large_radius(m, r_cell);
  m.cell = 2 * r_cell + m.skin;
  // Body-level broad phase (neighbour.h part_near): each body tests every other one when the list
  // is rebuilt, which pays while bodies are few against their sub-spheres (80 cabbages of 203,
  // 454 stalks of 720; not a bed of one-sphere bodies).
  uint64_t n_bodies = m.bodies.size();
  bool pays = n_bodies * n_bodies <= 8 * uint64_t(m.n_particles);
  if (n_bodies > 1 && spec.neighbour.body_broad_phase.value_or(pays)) m.flags |= gpu::kFlagBodyBroadPhase;
  m.table_size = next_pow2(std::max<uint32_t>(1024, 2 * m.n_particles));
  m.max_interval = spec.neighbour.rebuild_interval > 0 ? spec.neighbour.rebuild_interval : 0;
  m.still_interval = m.max_interval;

  // Moving walls: rebuild before any wall point can travel half the skin.
  double extent = 0;
  for (const auto& p : m.pos)
    extent = std::max(extent, std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z));
  double wall_speed = 0;
  for (const auto& w : m.walls) {
    double reach = w.radius + w.height + std::hypot(w.half_u, w.half_v);
    for (const Vec3d& p : {w.p0, w.p1, w.p2})
      reach = std::max(reach, std::sqrt(dot(p, p)));
    double lever = extent + std::sqrt(dot(w.motion.rotation_axis_point, w.motion.rotation_axis_point)) + reach;
    wall_speed = std::max(wall_speed, std::sqrt(dot(w.motion.velocity, w.motion.velocity)) +
                                          std::abs(w.motion.angular_rate) * lever);
  }
  if (wall_speed > 0) {
    auto steps = static_cast<uint32_t>(std::max(1.0, std::floor(0.5 * m.skin / (wall_speed * m.dt))));
    m.max_interval = m.max_interval ? std::min(m.max_interval, steps) : steps;
  }
}

// Each wall's named wall and its row among the moving ones (gpu::WallState info.w and topo.w).
void index_walls(Model& m) {
  std::vector<size_t> group = m.wall_groups();
  for (size_t w = 0; w < m.walls.size(); ++w) {
    ModelWall& mw = m.walls[w];
    mw.group = static_cast<uint32_t>(group[w]);
    if (!has_motion(mw.motion)) continue;
    m.moving_walls.push_back(static_cast<uint32_t>(w));
    mw.moving_row = static_cast<uint32_t>(m.moving_walls.size());
  }
  m.n_wall_groups = static_cast<uint32_t>(m.wall_group_names().size());
}

}  // namespace

Model build_model(const CaseSpec& spec) {
  Model m;
  m.case_path = spec.path;
  m.n_particles = static_cast<uint32_t>(spec.spheres.size());
  m.n_materials = static_cast<uint32_t>(spec.materials.size());
  if (spec.spheres.empty() && spec.bodies.empty())
    throw std::runtime_error(spec.path + ": the case has no particles");
  if (!spec.bodies.empty()) add_bodies(spec, m);
  else add_spheres(spec, m);
  add_pairs(spec, m);
  for (size_t wi = 0; wi < spec.walls.size(); ++wi) add_wall(spec, wi, m);

  m.rayleigh_time = rayleigh_time(spec);
  m.dt = resolve_dt(spec);
  m.end_time = spec.time.end_time;
  m.output_interval = spec.output.interval;
  m.checkpoint_interval = spec.output.checkpoint_interval;
  m.vtk = spec.output.vtk;
  m.gravity = spec.gravity;
  m.integrator = spec.integrator;
  set_contact_flags(spec, m);
  choose_neighbour_search(spec, m);
  index_walls(m);
  if (spec.neighbour.wall_grid.value_or(wall_grid_pays(m))) set_wall_grid(m);
  return m;
}

}  // namespace repose
