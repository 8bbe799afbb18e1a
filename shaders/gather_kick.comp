#version 450
// Kernel body: k_gather_kick in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_gather_kick(invocation_index()); }
