// Lets the kernel bodies in shaders/kernels/*.h compile as C++ for the CPU twin (kernels_ref/).
// GLM gives GLSL's vector types, the functions below its integer atomics, the macros its parameter
// qualifiers; buffer names resolve as members of the twin's kernel struct (kernels_ref/twin_kernels.h).
// Bit-exactness with lavapipe rests on: no FMA contraction (-ffp-contract=off), float literals
// written with an f suffix in shared code (a double literal would promote the expression), and
// scalar math from <cmath> (sqrt, floor are correctly rounded / exact).
#pragma once
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace repose::gpu {
using uint = std::uint32_t;
using glm::ivec3;
using glm::uvec4;
using glm::vec3;
using glm::vec4;
using std::abs;
using std::floor;
using std::max;
using std::min;
using std::sqrt;

// The contact law's dialect (kernels/contact_law.h) on one contact: a real is a float, a cond a
// bool (the SIMD lanes give these names one float per contact, kernels_ref/contact_lanes.cpp).
using real = float;
using real3 = vec3;
using cond = bool;
inline float pick(bool c, float yes, float no) { return c ? yes : no; }
inline vec3 pick(bool c, vec3 yes, vec3 no) { return c ? yes : no; }

// The twin's division and square root are IEEE's, correctly rounded; the GLSL kernels make
// theirs the same on devices that round otherwise (kernels/glsl_prelude.glsl).
inline float div_rn(float a, float b) { return a / b; }
inline float sqrt_rn(float x) { return std::sqrt(x); }

inline float uintBitsToFloat(uint u) { return std::bit_cast<float>(u); }

inline uint atomicAdd(uint& target, uint value) {
  return std::atomic_ref<uint>(target).fetch_add(value, std::memory_order_relaxed);
}
inline uint atomicOr(uint& target, uint value) {
  return std::atomic_ref<uint>(target).fetch_or(value, std::memory_order_relaxed);
}
inline uint atomicMax(uint& target, uint value) {
  std::atomic_ref<uint> ref(target);
  uint seen = ref.load(std::memory_order_relaxed);
  while (seen < value && !ref.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
  }
  return seen;
}
}  // namespace repose::gpu

// GLSL's `precise` has no C++ meaning: C++ already evaluates as written without fast-math flags.
#define precise
#define INOUT(T) T&
#define OUT(T) T&
