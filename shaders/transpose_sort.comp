#version 450
// Kernel body: k_transpose_sort in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_transpose_sort(invocation_index()); }
