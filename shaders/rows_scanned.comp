#version 450
// Kernel body: k_rows_scanned in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() {
  if (invocation_index() == 0u) k_rows_scanned(0u);  // one invocation decides
}
