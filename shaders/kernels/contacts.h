// Contact forces: one invocation per contact (or per owner row, the `rows` variant), both
// calling process_contact, which writes the contact's force and torques and updates its history.
// Two storage formats per contact (SimPush::flags kFlagLeanContacts):
//   full  contact_force (F_i, Fn), torque_i (T_i), torque_j (T_j)         48 B, gather_kick
//   lean  contact_force (F_i, mu_r|Fn| or -1), torque_i (n x Ft, overlap)  32 B, gather_lean,
//         which rebuilds T_i and T_j from these, the radii and the spins with body_torque().
#ifndef REPOSE_KERNELS_CONTACTS_H
#define REPOSE_KERNELS_CONTACTS_H

// A body's part of the spinning friction limiter (contact_law.h): the entries of its contact
// lists times 1 / its moment of inertia about n. A sphere's 1/I is omega.w; a clump's is
// n . (R I^-1 R^T n) from its principal moments, and its entries those of all its sub-spheres
// (contiguous, so two differences of the scanned row starts).
KFN(float, spin_stop_share) uint i, vec3 n) {
  uint first = i;
  uint count = 1u;
  precise float inv_i = B_omega[i].w;
  if ((PC.flags & kFlagBodies) != 0u) {
    uint b = B_subs[i].info.x;
    first = B_bodies[b].spheres.x;
    count = B_bodies[b].spheres.y;
    vec3 nb = quat_rotate_inverse(B_bodies[b].quat, n);
    vec3 m = xyz(B_bodies[b].inv_inertia);
    inv_i = (nb.x * nb.x) * m.x + (nb.y * nb.y) * m.y + (nb.z * nb.z) * m.z;
  }
  uint last = first + count;
  uint entries = (B_row_start[last] - B_row_start[first]) + (B_trans_start[last] - B_trans_start[first]);
  precise float share = float(max(entries, 1u)) * inv_i;
  return share;
}

KFN(void, process_contact) uint i, uint c) {
  uint p = B_partner[c];
  vec4 pi = B_pos[i];
  vec4 vi = B_vel[i];
  vec3 xi = xyz(pi);
  float rad_i = pi.w;
  vec3 wi = xyz(B_omega[i]);
  vec4 hist = B_history[c];
  vec3 shear = xyz(hist);
  uint mi = B_material[i];
  bool is_wall = p >= PC.n_particles;

  vec3 n = vec3(0.0f);
  float overlap = -1.0f;
  float radius_star = 0.0f;
  float mass_star = 0.0f;
  float ri = 0.0f;
  float rj = 0.0f;
  vec3 v_rel = vec3(0.0f);
  vec3 wj = vec3(0.0f);
  vec3 w_wall = vec3(0.0f);  // a wall's spin, for the rolling spring (rolls relative to the wall)
  float inv_inertia_r = 0.0f;  // 1 / (7/5 m r^2) summed over the two bodies (rolling dashpot)
  uint mj = 0u;
  bool touching = false;

  if (!is_wall) {
    vec4 pj = B_pos[p];
    vec4 vj = B_vel[p];
    float rad_j = pj.w;
    wj = xyz(B_omega[p]);
    mj = B_material[p];
    precise vec3 d = xi - xyz(pj);
    precise float dist = length3(d);
    overlap = rad_i + rad_j - dist;
    touching = overlap > 0.0f && dist > 0.0f;
    if (touching) {
      n = vec3(d.x / dist, d.y / dist, d.z / dist);
      radius_star = (rad_i * rad_j) / (rad_i + rad_j);
      mass_star = 1.0f / (vi.w + vj.w);
      ri = rad_i - 0.5f * overlap;
      rj = rad_j - 0.5f * overlap;
      precise vec3 spin = scale3(wi, ri) + scale3(wj, rj);
      v_rel = (xyz(vi) - xyz(vj)) - cross3(spin, n);
      inv_inertia_r = vi.w / (1.4f * (ri * ri)) + vj.w / (1.4f * (rj * rj));
    }
  } else {
    WallState ws = B_walls[PC.wall_slot * PC.n_walls + (p - PC.n_particles)];
    mj = ws.info.y;
    uint feature = kFeatureFace;
    touching = wall_contact_feature(ws, xi, rad_i, 0.0f, n, overlap, feature) && overlap > 0.0f;
    if (touching && ws.info.x == kWallTriangle)
      touching = !mesh_contact_shadowed(KB i, c, ws, p - PC.n_particles, xi, rad_i, overlap, feature);
    if (touching) {
      radius_star = rad_i;
      mass_star = 1.0f / vi.w;
      ri = rad_i - 0.5f * overlap;
      precise vec3 v_wall = wall_point_velocity(ws, contact_point(xi, n, ri));
      v_rel = (xyz(vi) - v_wall) - cross3(scale3(wi, ri), n);
      w_wall = xyz(ws.omega);
      inv_inertia_r = vi.w / (1.4f * (ri * ri));
    }
  }

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
  PairParams pp = B_pairs[mi * PC.n_materials + mj];
  float lever_i = ri;
  float lever_j = rj;
  if (centre_lever(PC.flags) && (PC.flags & kFlagLeanContacts) == 0u) {  // lean: the gather's job
    vec3 cp = contact_point(xi, n, ri);
    lever_i = rolling_lever(KB i, cp, ri);
    if (!is_wall) lever_j = rolling_lever(KB p, cp, rj);
  }
  ContactOut o = hertz_mindlin(n, overlap, radius_star, mass_star, ri, rj, lever_i, lever_j, v_rel, wi, wj,
                               is_wall, pp, PC.dt, PC.flags, shear);
  if ((PC.flags & kFlagKeepHistory) == 0u) B_history[c] = vec4(shear, hist.w + 1.0f);
  if (rolling_spring) {
    // Full entries only (the host refuses lean ones): the torque is stored per contact.
    vec3 spring = xyz(B_rolling_spring[c]);
    vec3 w_other = is_wall ? w_wall : wj;
    vec3 tr = epsd_rolling_torque(n, wi, w_other, radius_star, o.grip_force, o.normal_stiffness, pp.b.x,
                                  1.0f / inv_inertia_r, PC.rolling_damping, PC.dt, spring);
    o.torque_i = o.torque_i + tr;
    if (!is_wall) o.torque_j = o.torque_j - tr;
    if ((PC.flags & kFlagKeepHistory) == 0u) B_rolling_spring[c] = vec4(spring, 0.0f);
  }
  if ((PC.flags & kFlagSpinningFriction) != 0u && pp.c.x > 0.0f) {
    // Full entries only (the host refuses lean ones), like the rolling spring.
    vec3 w_other = is_wall ? w_wall : wj;
    precise float share = spin_stop_share(KB i, n);
    if (!is_wall) share = share + spin_stop_share(KB p, n);
    vec3 ts = spinning_friction_torque(n, wi, w_other, pp.c.x, radius_star, o.grip_force, share, PC.dt);
    o.torque_i = o.torque_i + ts;
    if (!is_wall) o.torque_j = o.torque_j - ts;
  }
  if (lean) {
    B_contact_force[c] = vec4(o.force_i, o.roll_arm);
    B_torque_i[c] = vec4(o.n_x_ft, overlap);
  } else {
    B_contact_force[c] = vec4(o.force_i, o.normal_force);
    B_torque_i[c] = vec4(o.torque_i, 0.0f);
    B_torque_j[c] = vec4(o.torque_j, 0.0f);
  }
}

// Variant "contact": one invocation per contact of the list.
KERNEL(k_contact_forces) uint c) {
  if (c >= B_control[kCtlContacts]) return;
  process_contact(KB B_owner[c], c);
}

// Variant "rows": one invocation per owner walks its own row in order.
KERNEL(k_contact_rows) uint i) {
  if (i >= PC.n_particles) return;
  uint limit = B_control[kCtlContacts];
  uint end = min(B_row_start[i + 1u], limit);
  for (uint c = min(B_row_start[i], limit); c < end; ++c) process_contact(KB i, c);
}

#endif
