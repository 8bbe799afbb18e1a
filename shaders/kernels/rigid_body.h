// A rigid body's sub-spheres (bodies.h) in the contact law's dialect (contact_law.h), written
// once for the GLSL kernels, the CPU twin and the twin's SIMD lanes (kernels_ref/body_lanes.cpp):
// all three place a sub-sphere and add its force to its body's with the same operations in the
// same order. No include guard: the lanes include it again inside their own struct; bodies.h
// includes it once.

// v rotated by the unit quaternion (u, w): v + 2 w (u x v) + 2 u x (u x v).
real3 rotate_by(real3 u, real w, real3 v) {
  precise real3 t = scale3(cross3(u, v), 2.0f);
  precise real3 r = v + scale3(t, w) + cross3(u, t);
  return r;
}

// The sub-sphere at body-frame offset `local` of a body at c, moving at v, turning at w and turned
// by the quaternion (u, qw): its arm r from c, its centre x and its velocity vx.
void place_sub(real3 c, real3 v, real3 w, real3 u, real qw, real3 local, OUT(real3) r, OUT(real3) x,
               OUT(real3) vx) {
  r = rotate_by(u, qw, local);
  precise real3 at = c + r;
  precise real3 moving = v + cross3(w, r);
  x = at;
  vx = moving;
}

// Adds a sub-sphere's force fs and torque ts (about its centre), at arm r, to its body's sums.
void add_sub_force(INOUT(real3) f, INOUT(real3) t, real3 r, real3 fs, real3 ts) {
  precise real3 f1 = f + fs;
  precise real3 t1 = t + cross3(r, fs);
  precise real3 t2 = t1 + ts;
  f = f1;
  t = t2;
}
