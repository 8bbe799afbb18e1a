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
#endif
