// 3-vector helpers in the contact law's dialect (contact_law.h): each written out left to right
// with `precise` temporaries, so lavapipe, g++ and the SIMD lanes evaluate the same operations in
// the same order. No include guard: the SIMD lanes include it again inside their own struct
// (kernels_ref/contact_lanes.cpp); common.h includes it once for the kernels.

real dot3(real3 a, real3 b) {
  precise real r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}

real3 cross3(real3 a, real3 b) {
  precise real x = a.y * b.z - a.z * b.y;
  precise real y = a.z * b.x - a.x * b.z;
  precise real z = a.x * b.y - a.y * b.x;
  return real3(x, y, z);
}

real length3(real3 a) {
  precise real r = sqrt_rn(dot3(a, a));
  return r;
}

real3 scale3(real3 a, real s) {
  precise real3 r = real3(a.x * s, a.y * s, a.z * s);
  return r;
}
