// GLSL side of the shared kernel code: buffer declarations named as the kernels use them, and
// the macros that the C++ twin defines differently (kernels_ref/cpu_kernels.cpp).
#extension GL_GOOGLE_include_directive : require
#include "repose_shared.h"

layout(local_size_x_id = 0) in;

#define FN
#define INOUT(T) inout T
#define OUT(T) out T
#define KERNEL(name) void name(
#define KFN(ret, name) ret name(
#define KB

// Every buffer of the table in repose_shared.h as B_name[].
#define REPOSE_DECLARE_BUFFER(index, Name, name, type, count, need, keep) \
  layout(std430, set = 0, binding = index) buffer Name##Buf { type B_##name[]; };
REPOSE_BUFFERS(REPOSE_DECLARE_BUFFER)
#undef REPOSE_DECLARE_BUFFER

#ifndef REPOSE_SCAN_PUSH
layout(push_constant) uniform PushBlock { SimPush PC; };
#endif
