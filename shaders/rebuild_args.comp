#version 450
// Kernel body: k_rebuild_args in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() {
  if (invocation_index() == 0u) k_rebuild_args(0u);  // one invocation decides
}
