#version 450
// Kernel body: k_bucket_sort in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_bucket_sort(invocation_index()); }
