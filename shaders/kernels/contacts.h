// Contact forces: one invocation per contact (or per owner row, the `rows` variant), both
// calling process_contact, which writes the contact's force and torques and updates its history.
// Two storage formats per contact (SimPush::flags kFlagLeanContacts):
//   full  contact_force (F_i, Fn), torque_i (T_i), torque_j (T_j)         48 B, gather_kick
//   lean  contact_force (F_i, mu_r|Fn| or -1), torque_i (n x Ft, overlap)  32 B, gather_lean,
//         which rebuilds T_i and T_j from these, the radii and the spins with body_torque().
#ifndef REPOSE_KERNELS_CONTACTS_H
#define REPOSE_KERNELS_CONTACTS_H

// Where spinning friction counts i's touching contacts: a clump's first sub-sphere's global id
// stands for its whole body.
uint touch_key(uint i) {
  if ((PC.flags & kFlagBodies) != 0u) return B_bodies[B_subs[i].info.x].spheres.x;
  return i;
}

// A body's part of the spinning friction limiter (contact_law.h): its touching contacts
// (touch_count, this step's) times 1 / its moment of inertia about n. A sphere's 1/I is
// omega.w; a clump's is n . (R I^-1 R^T n) from its principal moments, and its touching contacts
// those of all its sub-spheres. Touching ones only: list entries would make the result depend on
// the skin and the moments of rebuilding.
float spin_stop_share(uint i, vec3 n) {
  precise float inv_i = B_omega[i].w;
  if ((PC.flags & kFlagBodies) != 0u) {
    uint b = B_subs[i].info.x;
    vec3 nb = quat_rotate_inverse(B_bodies[b].quat, n);
    vec3 m = xyz(B_bodies[b].inv_inertia);
    inv_i = (nb.x * nb.x) * m.x + (nb.y * nb.y) * m.y + (nb.z * nb.z) * m.z;
  }
  precise float share = float(max(B_touches[touch_key(i)], 1u)) * inv_i;
  return share;
}

// process_contact's view of one touching contact.
struct ContactState {
  ContactGeometry g;
  vec3 v_rel;           // velocity of i's surface relative to j's at the contact point
  vec3 wj;              // j's spin (zero for a wall: the constant torques ignore a wall's spin)
  vec3 w_other;         // j's or the wall's spin (the EPSD spring and spinning friction count it)
  float inv_inertia_r;  // 1 / (7/5 m r^2) summed over the two bodies (rolling dashpot)
  uint mj;              // j's material
};

// The rolling levers of i and (unless a wall) p at the contact: the sphere's own ri, rj as the
// geometry holds them, or for EDEM's torque on a clump the distance to its centre of mass (full
// entries; the lean gather measures them itself).
void set_rolling_levers(uint i, uint p, vec3 xi, bool is_wall, INOUT(ContactGeometry) g) {
  if (!centre_lever(PC.flags) || (PC.flags & kFlagLeanContacts) != 0u) return;
  vec3 cp = contact_point(xi, g.n, g.ri);
  g.lever_i = rolling_lever(i, cp, g.ri);
  if (!is_wall) g.lever_j = rolling_lever(p, cp, g.rj);
}

// A particle as touching_spheres() (contact_law.h) takes it.
SphereState sphere_state(uint k) {
  SphereState s;
  vec4 p = B_pos[k];
  vec4 v = B_vel[k];
  s.x = xyz(p);
  s.radius = p.w;
  s.v = xyz(v);
  s.inv_mass = v.w;
  s.w = xyz(B_omega[k]);
  return s;
}

// Contact of particles i and p: false when they do not touch.
bool touch_particle(uint i, uint p, OUT(ContactState) s) {
  SphereState si = sphere_state(i);
  SphereState sj = sphere_state(p);
  s.wj = sj.w;
  s.w_other = sj.w;
  s.mj = B_material[p];
  if (!touching_spheres(si, sj, PC.flags, s.g, s.v_rel)) return false;
  precise float inv_inertia_r = div_rn(si.inv_mass, 1.4f * (s.g.ri * s.g.ri)) + div_rn(sj.inv_mass, 1.4f * (s.g.rj * s.g.rj));
  s.inv_inertia_r = inv_inertia_r;
  set_rolling_levers(i, p, si.x, false, s.g);
  return true;
}

// Contact of particle i with wall row p - n_particles (contact c): false when not touching.
bool touch_wall(uint i, uint c, uint p, OUT(ContactState) s) {
  SphereState si = sphere_state(i);
  WallState ws = wall_at(p - PC.n_particles);
  s.mj = ws.info.y;
  s.wj = vec3(0.0f);
  s.w_other = xyz(ws.omega);
  uint feature = kFeatureFace;
  vec3 n;
  float overlap;
  bool touching = wall_contact_feature(ws, si.x, si.radius, 0.0f, n, overlap, feature) && overlap > 0.0f;
  if (touching && wall_kind_possible(kWallTriangle) && ws.info.x == kWallTriangle)
    touching = !mesh_contact_shadowed(i, c, ws, p - PC.n_particles, si.x, si.radius, overlap, feature);
  if (!touching) return false;
  wall_geometry(si, n, overlap, xyz(ws.vel), xyz(ws.omega), xyz(ws.centre), PC.flags, s.g, s.v_rel);
  precise float inv_inertia_r = div_rn(si.inv_mass, 1.4f * (s.g.ri * s.g.ri));
  s.inv_inertia_r = inv_inertia_r;
  set_rolling_levers(i, p, si.x, true, s.g);
  return true;
}

void process_contact(uint i, uint c) {
  uint p = B_partner[c];
  vec3 wi = xyz(B_omega[i]);
  vec4 hist = B_history[c];
  vec3 shear = xyz(hist);
  uint mi = B_material[i];
  bool is_wall = p >= PC.n_particles;
  ContactState st;
  bool touching = is_wall ? touch_wall(i, c, p, st) : touch_particle(i, p, st);

  bool lean = (PC.flags & kFlagLeanContacts) != 0u;
  bool rolling_spring = (PC.flags & kFlagRollingSpring) != 0u;
  if (!touching) {
    if (rolling_spring) B_rolling_spring[c] = vec4(0.0f);
    // Separated: the tangential history ends with the contact (LIGGGHTS, EDEM). Lean: overlap 0
    // tells gather_lean that the torques are zero.
    B_history[c] = vec4(0.0f);
    B_contact_force[c] = vec4(0.0f);
    B_torque_i[c] = vec4(0.0f);
    if (!lean) B_torque_j[c] = vec4(0.0f);
    return;
  }
  PairParams pp = B_pairs[mi * PC.n_materials + st.mj];
  vec3 n = st.g.n;
  ContactOut o = hertz_mindlin(st.g, st.v_rel, wi, st.wj, is_wall, pp, PC.dt, PC.flags, shear);
  if ((PC.flags & kFlagKeepHistory) == 0u) B_history[c] = vec4(shear, hist.w + 1.0f);
  if (rolling_spring) {
    // Full entries only (the host refuses lean ones): the torque is stored per contact.
    vec3 spring = xyz(B_rolling_spring[c]);
    vec3 tr = epsd_rolling_torque(n, wi, st.w_other, st.g.radius_star, o.grip_force, o.normal_stiffness, pp.rolling_friction,
                                  div_rn(1.0f, st.inv_inertia_r), PC.rolling_damping, PC.dt, spring);
    o.torque_i = o.torque_i + tr;
    if (!is_wall) o.torque_j = o.torque_j - tr;
    if ((PC.flags & kFlagKeepHistory) == 0u) B_rolling_spring[c] = vec4(spring, 0.0f);
  }
  if ((PC.flags & kFlagSpinningFriction) != 0u && pp.spinning_friction > 0.0f) {
    // Full entries only (the host refuses lean ones), like the rolling spring.
    precise float share = spin_stop_share(i, n);
    if (!is_wall) share = share + spin_stop_share(p, n);
    vec3 ts = spinning_friction_torque(n, wi, st.w_other, pp.spinning_friction, st.g.radius_star, o.grip_force, share, PC.dt);
    o.torque_i = o.torque_i + ts;
    if (!is_wall) o.torque_j = o.torque_j - ts;
  }
  if (lean) {
    B_contact_force[c] = vec4(o.force_i, o.roll_arm);
    B_torque_i[c] = vec4(o.n_x_ft, st.g.overlap);
  } else {
    B_contact_force[c] = vec4(o.force_i, o.normal_force);
    B_torque_i[c] = vec4(o.torque_i, 0.0f);
    B_torque_j[c] = vec4(o.torque_j, 0.0f);
  }
}

void k_clear_touches(uint i) {
  if (i >= PC.n_particles) return;
  B_touches[i] = 0u;
}

// Counts contact c for both its bodies when it touches, by the contact kernel's own test (an
// integer sum: the same in any order).
void k_touch_count(uint c) {
  if (c >= B_control[kCtlContacts]) return;
  uint i = B_owner[c];
  uint p = B_partner[c];
  bool is_wall = p >= PC.n_particles;
  ContactState st;
  bool touching = is_wall ? touch_wall(i, c, p, st) : touch_particle(i, p, st);
  if (!touching) return;
  atomicAdd(B_touches[touch_key(i)], 1u);
  if (!is_wall) atomicAdd(B_touches[touch_key(p)], 1u);
}

// Variant "contact": one invocation per contact of the list.
void k_contact_forces(uint c) {
  if (c >= B_control[kCtlContacts]) return;
  process_contact(B_owner[c], c);
}

// Variant "rows": one invocation per owner walks its own row in order.
void k_contact_rows(uint i) {
  if (i >= PC.n_particles) return;
  uint limit = B_control[kCtlContacts];
  uint end = min(B_row_start[i + 1u], limit);
  for (uint c = min(B_row_start[i], limit); c < end; ++c) process_contact(i, c);
}

#endif
