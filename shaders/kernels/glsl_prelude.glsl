// GLSL side of the shared kernel code: buffer declarations named as the kernels use them (the
// C++ twin has the same names as members of the struct the bodies are compiled in,
// kernels_ref/twin_kernels.h), and the parameter qualifiers that the twin maps to references.
#extension GL_GOOGLE_include_directive : require
#include "repose_shared.h"

layout(local_size_x_id = 0) in;

// This invocation's index over the whole dispatch, counting across rows of workgroups along y
// (a dispatch above the device's workgroup count along x is split: dispatch_rows in
// repose_shared.h). The CPU twin runs the same indices in order.
uint invocation_index() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
}

// Correctly rounded division and square root on every device (docs/engineering.md, determinism).
// The device's result is checked exactly in double precision (a float times a float fits a
// double, and the difference of two nearly equal doubles is exact) against its neighbours, and
// the one nearest the true value is kept. With kRoundingDevice the device's result stands.
layout(constant_id = 3) const uint kRounding = kRoundingDevice;

float step_ulps(float v, int k) { return uintBitsToFloat(uint(int(floatBitsToUint(v)) + k)); }

// kRoundingTest: `v` moved by -2 ... +2 ULP, by a hash of the operands.
float nudged(float v, uint seed) {
  float c = step_ulps(v, int((seed * 2654435761u) >> 29u) % 5 - 2);
  return (isnan(c) || isinf(c) || sign(c) != sign(v)) ? v : c;
}

// The float next to v, above it in value (up) or below.
float next_float(float v, bool up) { return step_ulps(v, up == (v > 0.0f) ? 1 : -1); }

float div_rn(float a, float b) {
  precise float q = a / b;
  if (kRounding == kRoundingDevice || isnan(q) || isinf(q) || q == 0.0f) return q;
  if (kRounding == kRoundingTest) q = nudged(q, floatBitsToUint(a) ^ (floatBitsToUint(b) << 7u));
  // a/b = q + r/b with r = a - q b exact: step towards a/b while the next float has a smaller
  // |r| (the nearest float to a/b has the smallest; ties cannot happen). Usually one check.
  precise double da = double(a), db = double(b);
  precise double r = da - double(q) * db;
  bool up = (r > 0.0lf) == (b > 0.0f);
  for (int k = 0; k < 4; ++k) {
    float c = next_float(q, up);
    precise double rc = da - double(c) * db;
    if (isnan(c) || isinf(c) || !(abs(rc) < abs(r))) break;
    q = c;
    r = rc;
  }
  return q;
}

float sqrt_rn(float x) {
  precise float s = sqrt(x);
  if (kRounding == kRoundingDevice || !(s > 0.0f) || isinf(s)) return s;
  if (kRounding == kRoundingTest) s = nudged(s, floatBitsToUint(x));
  // s is the nearest float to sqrt(x) when x lies between the squares of the midpoints to its
  // neighbours (a midpoint has 25 bits, its square 50: exact in double).
  precise double dx = double(x);
  for (int k = 0; k < 4; ++k) {
    precise double up = 0.5lf * (double(s) + double(step_ulps(s, 1)));
    if (dx <= up * up) break;
    s = step_ulps(s, 1);
  }
  for (int k = 0; k < 4; ++k) {
    precise double down = 0.5lf * (double(s) + double(step_ulps(s, -1)));
    if (dx >= down * down) break;
    s = step_ulps(s, -1);
  }
  return s;
}

#define INOUT(T) inout T
#define OUT(T) out T

// The contact law's dialect (kernels/contact_law.h): here a real is a float, a cond a bool, and
// pick() GLSL's selection. The SIMD lanes give the same names one float per contact.
#define real float
#define real3 vec3
#define cond bool
float pick(bool c, float yes, float no) { return c ? yes : no; }
vec3 pick(bool c, vec3 yes, vec3 no) { return c ? yes : no; }

// Every buffer of the table in repose_shared.h as B_name[].
#define REPOSE_DECLARE_BUFFER(index, Name, name, type, count, need, keep) \
  layout(std430, set = 0, binding = index) buffer Name##Buf { type B_##name[]; };
REPOSE_BUFFERS(REPOSE_DECLARE_BUFFER)
#undef REPOSE_DECLARE_BUFFER

#ifndef REPOSE_SCAN_PUSH
layout(push_constant) uniform PushBlock { SimPush PC_pushed; };
// The flags word as a specialisation constant (host/vk/kernel_set.cpp builds one pipeline per
// kernel and flags): the compiler then drops the code of every feature that is off. lavapipe
// (Mesa 22) runs both sides of every branch under a lane mask, so that code costs time even
// when no invocation takes it. The kernels read PC.flags as before; the twin reads the push.
layout(constant_id = 1) const uint kSpecialisedFlags = 0u;
// Likewise the wall kinds the run has none of: their code goes too (wall_kind_possible()).
layout(constant_id = 2) const uint kSpecialisedAbsentWallKinds = 0u;
SimPush pc_specialised() {
  SimPush p = PC_pushed;
  p.flags = kSpecialisedFlags;
  p.absent_wall_kinds = kSpecialisedAbsentWallKinds;
  return p;
}
#define PC pc_specialised()
// False when the run has no wall of this kind: lavapipe then compiles the kind's code out
// instead of running it under a lane mask. The twin's is always true (kernels_ref/twin_kernels.h).
bool wall_kind_possible(uint kind) { return (PC.absent_wall_kinds & (1u << kind)) == 0u; }
// The walk of a row of cells and of the large bucket (kernels/neighbour.h): walk_cells and
// walk_large here; the twin may test their slots in SIMD lanes instead (kernels_ref/twin_kernels.h,
// walk_lanes.h), finding the same candidates in the same order.
#define walk_row walk_cells
#define walk_large_bucket walk_large
#endif
