#version 450
// Kernel body: k_contact_fill in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_contact_fill(invocation_index()); }
