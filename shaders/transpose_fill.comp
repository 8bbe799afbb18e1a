#version 450
// Kernel body: k_transpose_fill in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_transpose_fill(invocation_index()); }
