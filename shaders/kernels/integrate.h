// Time integration of translation and rotation. Velocity Verlet = kick(1/2) drift | forces |
// gather + kick(1/2); symplectic Euler = forces | gather + kick(1) drift. Spheres only need the
// angular velocity (no orientation).
#ifndef REPOSE_KERNELS_INTEGRATE_H
#define REPOSE_KERNELS_INTEGRATE_H

#include "kernels/kick.h"

// v += kick dt (F/m + g [+ drag]); w += kick dt T/I; then, with kFlagDrift, x += dt v and the skin check.
void kick_and_drift(uint i, vec3 force, vec3 torque) {
  vec4 v4 = B_vel[i];
  if (v4.w == 0.0f) return;  // fixed (neighbour.h): never moves
  vec4 w4 = B_omega[i];
  precise float h = PC.kick * PC.dt;
  bool drag = PC.air_drag > 0.0f;
  precise float drag_area = 0.0f;
  if (drag) {
    float r = B_pos[i].w;
    drag_area = PC.air_drag * (r * r);
  }
  vec3 v = kicked_velocity(xyz(v4), force, v4.w, vec3(PC.gx, PC.gy, PC.gz), h, drag, drag_area);
  vec3 w = kicked_spin(xyz(w4), torque, w4.w, h);
  B_vel[i] = vec4(v, v4.w);
  B_omega[i] = vec4(w, w4.w);
  if ((PC.flags & kFlagDrift) != 0u) {
    vec4 p4 = B_pos[i];
    vec3 x = drifted(xyz(p4), v, PC.dt);
    B_pos[i] = vec4(x, p4.w);
    precise vec3 moved = x - xyz(B_pos_at_build[i]);
    if (dot3(moved, moved) > PC.half_skin_sq) atomicOr(B_control[kCtlNeedRebuild], 1u);
  }
}

// First half of a velocity Verlet step, with the forces of the previous step.
void k_kick_drift(uint i) {
  if (i >= PC.n_particles) return;
  kick_and_drift(i, xyz(B_force[i]), xyz(B_torque[i]));
}

// Sums particle i's contact forces in a fixed order (its own row, then the contacts in which it
// is the partner, by contact index) and stores them; f and t are the sums.
void gather_contact_sums(uint i, OUT(vec3) f, OUT(vec3) t) {
  uint limit = B_control[kCtlContacts];
  precise vec3 fs = vec3(0.0f);
  precise vec3 ts = vec3(0.0f);
  uint end = min(B_row_start[i + 1u], limit);
  for (uint c = min(B_row_start[i], limit); c < end; ++c) {
    fs = fs + xyz(B_contact_force[c]);
    ts = ts + xyz(B_torque_i[c]);
  }
  uint tend = B_trans_start[i + 1u];
  for (uint k = B_trans_start[i]; k < tend; ++k) {
    uint c = B_trans_list[k];
    fs = fs - xyz(B_contact_force[c]);
    ts = ts + xyz(B_torque_j[c]);
  }
  B_force[i] = vec4(fs, 0.0f);
  B_torque[i] = vec4(ts, 0.0f);
  f = fs;
  t = ts;
}

// Each particle's contact forces summed and stored, then the step finished.
void k_gather_kick(uint i) {
  if (i >= PC.n_particles) return;
  vec3 f;
  vec3 t;
  gather_contact_sums(i, f, t);
  if (PC.kick > 0.0f) kick_and_drift(i, f, t);
}

// The rolling lever of particle k at contact point cp (centre_of_mass_lever() in contact_law.h).
float rolling_lever(uint k, vec3 cp, float r) {
  uint b = B_subs[k].info.x;
  return centre_of_mass_lever(cp, xyz(B_bodies[b].pos), r, B_bodies[b].spheres.y < 2u);
}

// The unit normal of stored contact c, recomputed from the positions exactly as process_contact
// computed it (positions do not move between the contact kernel and a gather that calls this).
vec3 stored_contact_normal(uint c) {
  uint i = B_owner[c];
  uint p = B_partner[c];
  vec4 pi = B_pos[i];
  vec3 n = vec3(0.0f, 0.0f, 1.0f);
  if (p < PC.n_particles) {
    precise vec3 d = xyz(pi) - xyz(B_pos[p]);
    precise float dist = length3(d);
    n = vec3(div_rn(d.x, dist), div_rn(d.y, dist), div_rn(d.z, dist));
  } else {
    WallState ws = wall_at(p - PC.n_particles);
    float overlap;
    uint feature;
    wall_contact_feature(ws, xyz(pi), pi.w, 0.0f, n, overlap, feature);
  }
  return n;
}

// A lean entry's rolling lever for particle `self` (the owner when owner_side) with sphere lever
// r: the centre-of-mass distance from the contact point process_contact used.
float lean_rolling_lever(uint c, uint self, float r, float overlap) {
  vec4 pi = B_pos[B_owner[c]];
  vec3 n = stored_contact_normal(c);
  precise float ri = pi.w - 0.5f * overlap;
  return rolling_lever(self, contact_point(xyz(pi), n, ri), r);
}

// The torque a lean contact entry (contacts.h) puts on one of its bodies, with exactly the
// arithmetic process_contact uses for the full entry: `rad` and `w` are that body's radius and
// spin, `owner_side` tells i (+tr) from j (-tr). The relative rolling torque needs both spins
// and radii (only with kFlagRollingRelativeOmega; the step program then kicks in a separate
// pass so no spin changes while gathers read it).
vec3 lean_torque(uint c, uint self, bool owner_side, float rad, vec3 w, float lw, vec4 a, vec4 b) {
  if (!(b.w > 0.0f)) return vec3(0.0f);  // separated: the full entry stores zeros
  bool relative = (PC.flags & kFlagRollingRelativeOmega) != 0u;
  precise float r = rad - 0.5f * b.w;
  float lever = r;
  if (a.w >= 0.0f && centre_lever(PC.flags)) lever = lean_rolling_lever(c, self, r, b.w);
  vec3 t = body_torque(xyz(b), r, relative ? -1.0f : a.w, lever, w, lw);
  if (relative && a.w >= 0.0f) {
    uint i = B_owner[c];
    uint p = B_partner[c];
    vec4 pi = B_pos[i];
    vec3 wi = xyz(B_omega[i]);
    vec3 wj = vec3(0.0f);
    precise float lever = pi.w - 0.5f * b.w;  // a wall: LIGGGHTS's contact radius r_i - dn/2
    if (p < PC.n_particles) {
      float rad_j = B_pos[p].w;
      wj = xyz(B_omega[p]);
      lever = div_rn(pi.w * rad_j, pi.w + rad_j);  // R*
    }
    vec3 tr;
    if (relative_rolling(wi, wj, a.w, lever, stored_contact_normal(c), tr)) t = owner_side ? t + tr : t - tr;
  }
  return t;
}

// Variant "lean": the gather of gather_kick (same order, same sums) from lean contact entries.
// Both lists go through one loop, so an invocation with a long own row and a short transposed
// row (or the reverse) keeps its SIMD lanes busy on lavapipe.
void k_gather_lean(uint i) {
  if (i >= PC.n_particles) return;
  uint limit = B_control[kCtlContacts];
  vec4 pi = B_pos[i];
  vec3 wi = xyz(B_omega[i]);
  precise float lwi = length3(wi);  // |w_i| once, not per contact
  precise vec3 f = vec3(0.0f);
  precise vec3 t = vec3(0.0f);
  uint begin = min(B_row_start[i], limit);
  uint own = min(B_row_start[i + 1u], limit) - begin;
  uint tbegin = B_trans_start[i];
  uint total = own + (B_trans_start[i + 1u] - tbegin);
  for (uint k = 0u; k < total; ++k) {
    bool owner_side = k < own;
    uint c = owner_side ? begin + k : B_trans_list[tbegin + (k - own)];
    vec4 a = B_contact_force[c];
    vec4 b = B_torque_i[c];
    f = owner_side ? f + xyz(a) : f - xyz(a);
    t = t + lean_torque(c, i, owner_side, pi.w, wi, lwi, a, b);
  }
  B_force[i] = vec4(f, 0.0f);
  B_torque[i] = vec4(t, 0.0f);
  if (PC.kick > 0.0f) kick_and_drift(i, f, t);
}

#endif
