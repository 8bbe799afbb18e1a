#version 450
// Kernel body: k_save_old_rows in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_save_old_rows(invocation_index()); }
