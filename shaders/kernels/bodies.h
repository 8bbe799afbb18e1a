// Rigid bodies made of sub-spheres (multi-sphere clumps). The contact pipeline sees only the
// sub-spheres: body_place writes each sub-sphere's world position, velocity (the body's velocity
// at that point) and spin from its body; after the contact forces, body_gather_kick sums each
// body's sub-sphere forces and torques in sub-sphere order (by global id, whatever their slots:
// bit-exact between backends and storage orders) and integrates the body. Angular momentum L
// (world frame) is the integrated state: omega = R I^-1 R^T L with the diagonal principal
// inertia I, so a torque-free body keeps L to the bit, and the orientation advances by a midpoint
// rotation (second order; no trigonometry).
#ifndef REPOSE_KERNELS_BODIES_H
#define REPOSE_KERNELS_BODIES_H

#include "kernels/rigid_body.h"

// v rotated by the unit quaternion q.
vec3 quat_rotate(vec4 q, vec3 v) { return rotate_by(xyz(q), q.w, v); }

vec3 quat_rotate_inverse(vec4 q, vec3 v) { return quat_rotate(vec4(-q.x, -q.y, -q.z, q.w), v); }

// Hamilton product a b.
vec4 quat_mul(vec4 a, vec4 b) {
  vec3 u = xyz(a);
  vec3 v = xyz(b);
  precise float w = a.w * b.w - dot3(u, v);
  precise vec3 r = scale3(v, a.w) + scale3(u, b.w) + cross3(u, v);
  return vec4(r, w);
}

vec4 quat_normalize(vec4 q) {
  precise float len = sqrt_rn(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return vec4(div_rn(q.x, len), div_rn(q.y, len), div_rn(q.z, len), div_rn(q.w, len));
}

// Rotates q by the angular velocity w over time h: (w h/2, 1) q, normalised, is a rotation by
// 2 atan(|w| h / 2) = |w| h (1 - (|w| h)^2 / 12 + ...) about w.
vec4 quat_advance(vec4 q, vec3 w, float h) {
  precise float half_h = 0.5f * h;
  vec4 dq = vec4(scale3(w, half_h), 1.0f);
  return quat_normalize(quat_mul(dq, q));
}

// Angular velocity (world) of a body with orientation q, angular momentum L and inverse
// principal moments inv_i.
vec3 body_omega(vec4 q, vec3 L, vec3 inv_i) {
  vec3 lb = quat_rotate_inverse(q, L);
  precise vec3 wb = vec3(lb.x * inv_i.x, lb.y * inv_i.y, lb.z * inv_i.z);
  return quat_rotate(q, wb);
}

// v += kick dt (F/m + g); L += kick dt T; with kFlagDrift also x += dt v and the orientation
// advances over dt with the midpoint angular velocity (L is constant during the drift).
void body_kick_and_drift(uint b, vec3 force, vec3 torque) {
  vec4 p4 = B_bodies[b].pos;
  if (p4.w == 0.0f) return;  // a fixed body (1/mass = 0) never moves
  vec4 q = B_bodies[b].quat;
  vec3 inv_i = xyz(B_bodies[b].inv_inertia);
  precise float h = PC.kick * PC.dt;
  precise vec3 accel = scale3(force, p4.w) + vec3(PC.gx, PC.gy, PC.gz);
  if (PC.air_drag > 0.0f) {
    // Extension air_drag with the body's silhouette across its velocity: an ellipsoid's
    // A(d) = sqrt(sum (A_i d_i)^2) over the principal axes (exact for spheres and ellipsoids),
    // times |v| without a division: |(A_i v_i)| in the body frame.
    vec3 v_old = xyz(B_bodies[b].vel);
    vec3 vb = quat_rotate_inverse(q, v_old);
    vec4 d = B_bodies[b].drag;
    precise vec3 av = vec3(d.x * vb.x, d.y * vb.y, d.z * vb.z);
    precise float area_speed = length3(av);
    precise float k = -((PC.air_drag * p4.w) * area_speed);
    accel = accel + scale3(v_old, k);
  }
  precise vec3 v = xyz(B_bodies[b].vel) + scale3(accel, h);
  precise vec3 L = xyz(B_bodies[b].ang_mom) + scale3(torque, h);
  if ((PC.flags & kFlagDrift) != 0u) {
    precise vec3 x = xyz(p4) + scale3(v, PC.dt);
    B_bodies[b].pos = vec4(x, p4.w);
    vec3 w0 = body_omega(q, L, inv_i);
    vec4 q_half = quat_advance(q, w0, 0.5f * PC.dt);
    vec3 w_half = body_omega(q_half, L, inv_i);
    q = quat_advance(q, w_half, PC.dt);
    B_bodies[b].quat = q;
  }
  B_bodies[b].vel = vec4(v, 0.0f);
  B_bodies[b].ang_mom = vec4(L, 0.0f);
  B_bodies[b].omega = vec4(body_omega(q, L, inv_i), 0.0f);
}

// First half of a velocity Verlet step for bodies, with the forces of the previous step.
void k_body_kick_drift(uint b) {
  if (b >= PC.n_bodies) return;
  body_kick_and_drift(b, xyz(B_bodies[b].force), xyz(B_bodies[b].torque));
}

// Sub-sphere i from its body: position, velocity of the body at that point (w: the body's
// 1/mass, so the contact law's effective mass is the body's), spin. With kFlagDrift, the skin
// check of the neighbour list.
void k_body_place(uint i) {
  if (i >= PC.n_particles) return;
  vec4 local = B_subs[i].local;
  uint b = B_subs[i].info.x;
  vec4 p4 = B_bodies[b].pos;
  vec4 q = B_bodies[b].quat;
  vec3 w = xyz(B_bodies[b].omega);
  vec3 r;
  vec3 x;
  vec3 v;
  place_sub(xyz(p4), xyz(B_bodies[b].vel), w, xyz(q), q.w, xyz(local), r, x, v);
  B_pos[i] = vec4(x, local.w);
  B_vel[i] = vec4(v, p4.w);
  B_omega[i] = vec4(w, 0.0f);
  if ((PC.flags & kFlagDrift) != 0u) {
    precise vec3 moved = x - xyz(B_pos_at_build[i]);
    if (dot3(moved, moved) > PC.half_skin_sq) atomicOr(B_control[kCtlNeedRebuild], 1u);
  }
}

// Sums body b's sub-sphere forces and their torques about the centre of mass in sub-sphere
// order, stores them, and applies the kick (and drift) of the step.
void k_body_gather_kick(uint b) {
  if (b >= PC.n_bodies) return;
  uvec4 range = B_bodies[b].spheres;
  vec4 q = B_bodies[b].quat;
  vec3 f = vec3(0.0f);
  vec3 t = vec3(0.0f);
  for (uint g = range.x; g < range.x + range.y; ++g) {
    uint s = slot_of(g);
    vec3 r = quat_rotate(q, xyz(B_subs[s].local));  // the arm body_place used, to the bit
    add_sub_force(f, t, r, xyz(B_force[s]), xyz(B_torque[s]));
  }
  B_bodies[b].force = vec4(f, 0.0f);
  B_bodies[b].torque = vec4(t, 0.0f);
  if (PC.kick > 0.0f) body_kick_and_drift(b, f, t);
}

#endif
