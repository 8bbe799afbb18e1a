// A particle's kick and drift (integrate.h's kick_and_drift) in the contact law's dialect
// (contact_law.h), written once for the GLSL kernels, the CPU twin and the twin's SIMD lanes
// (kernels_ref/kick_lanes.cpp): all three kick and drift with the same operations in the same
// order. No include guard: the lanes include it again inside their own struct; integrate.h
// includes it once.

// Extension air_drag (docs/diagnosis.md): quadratic drag -(0.5 rho C_d A) |v| v / m, with
// drag_area = 0.5 rho C_d A for the sphere (PC.air_drag r^2) and inv_mass = 1/m. (A clump body's
// drag, from its silhouette across its velocity, is in bodies.h.)
real3 air_drag_acceleration(real3 v, real drag_area, real inv_mass) {
  precise real speed = length3(v);
  precise real k = -((drag_area * inv_mass) * speed);
  return scale3(v, k);
}

// v + h (F/m + g [+ drag]), with inv_mass = 1/m; `drag` is the same for every particle of a run.
real3 kicked_velocity(real3 v, real3 force, real inv_mass, real3 g, real h, bool drag, real drag_area) {
  precise real3 accel = scale3(force, inv_mass) + g;
  if (drag) accel = accel + air_drag_acceleration(v, drag_area, inv_mass);
  precise real3 kicked = v + scale3(accel, h);
  return kicked;
}

// w + h T/I, with inv_inertia = 1/I (a sphere's moment is the same about every axis).
real3 kicked_spin(real3 w, real3 torque, real inv_inertia, real h) {
  precise real3 kicked = w + scale3(torque, h * inv_inertia);
  return kicked;
}

// x + dt v.
real3 drifted(real3 x, real3 v, real dt) {
  precise real3 moved = x + scale3(v, dt);
  return moved;
}
