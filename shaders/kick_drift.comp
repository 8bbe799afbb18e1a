#version 450
// Kernel body: k_kick_drift in shaders/kernels/ (shared with the CPU twin).
#include "kernels/glsl_prelude.glsl"
#include "kernels/all.h"

void main() { k_kick_drift(invocation_index()); }
