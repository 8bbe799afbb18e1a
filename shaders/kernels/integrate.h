// Time integration of translation and rotation. Velocity Verlet = kick(1/2) drift | forces |
// gather + kick(1/2); symplectic Euler = forces | gather + kick(1) drift. Spheres only need the
// angular velocity (no orientation).
#ifndef REPOSE_KERNELS_INTEGRATE_H
#define REPOSE_KERNELS_INTEGRATE_H

// v += kick dt (F/m + g); w += kick dt T/I; then, with kFlagDrift, x += dt v and the skin check.
KFN(void, kick_and_drift) uint i, vec3 force, vec3 torque) {
  vec4 v4 = B_vel[i];
  vec4 w4 = B_omega[i];
  precise float h = PC.kick * PC.dt;
  precise vec3 accel = scale3(force, v4.w) + vec3(PC.gx, PC.gy, PC.gz);
  precise vec3 v = xyz(v4) + scale3(accel, h);
  precise vec3 w = xyz(w4) + scale3(torque, h * w4.w);
  B_vel[i] = vec4(v, v4.w);
  B_omega[i] = vec4(w, w4.w);
  if ((PC.flags & kFlagDrift) != 0u) {
    vec4 p4 = B_pos[i];
    precise vec3 x = xyz(p4) + scale3(v, PC.dt);
    B_pos[i] = vec4(x, p4.w);
    precise vec3 moved = x - xyz(B_pos_at_build[i]);
    if (dot3(moved, moved) > PC.half_skin_sq) atomicOr(B_control[kCtlNeedRebuild], 1u);
  }
}

// First half of a velocity Verlet step, with the forces of the previous step.
KERNEL(k_kick_drift) uint i) {
  if (i >= PC.n_particles) return;
  kick_and_drift(KB i, xyz(B_force[i]), xyz(B_torque[i]));
}

// Sum each particle's contact forces in a fixed order (its own row, then the contacts in which it
// is the partner, by contact index), store them, and finish the step.
KERNEL(k_gather_kick) uint i) {
  if (i >= PC.n_particles) return;
  uint limit = B_control[kCtlContacts];
  precise vec3 f = vec3(0.0f);
  precise vec3 t = vec3(0.0f);
  uint end = min(B_row_start[i + 1u], limit);
  for (uint c = min(B_row_start[i], limit); c < end; ++c) {
    f = f + xyz(B_contact_force[c]);
    t = t + xyz(B_torque_i[c]);
  }
  uint tend = B_trans_start[i + 1u];
  for (uint k = B_trans_start[i]; k < tend; ++k) {
    uint c = B_trans_list[k];
    f = f - xyz(B_contact_force[c]);
    t = t + xyz(B_torque_j[c]);
  }
  B_force[i] = vec4(f, 0.0f);
  B_torque[i] = vec4(t, 0.0f);
  if (PC.kick > 0.0f) kick_and_drift(KB i, f, t);
}

#endif
