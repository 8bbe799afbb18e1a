#version 450
// Kernel body: k_clear_buckets in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_clear_buckets(invocation_index()); }
