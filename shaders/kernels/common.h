// Math helpers shared by every kernel, GLSL and C++ alike. Each is written out left to right with
// `precise` temporaries so that lavapipe and g++ evaluate the same operations in the same order.
#ifndef REPOSE_KERNELS_COMMON_H
#define REPOSE_KERNELS_COMMON_H

vec3 xyz(vec4 v) { return vec3(v.x, v.y, v.z); }

float dot3(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}

vec3 cross3(vec3 a, vec3 b) {
  precise float x = a.y * b.z - a.z * b.y;
  precise float y = a.z * b.x - a.x * b.z;
  precise float z = a.x * b.y - a.y * b.x;
  return vec3(x, y, z);
}

float length3(vec3 a) {
  precise float r = sqrt_rn(dot3(a, a));
  return r;
}

vec3 scale3(vec3 a, float s) {
  precise vec3 r = vec3(a.x * s, a.y * s, a.z * s);
  return r;
}

// Groups of `workgroup` invocations needed to cover `count` items.
uint groups_for(uint count, uint workgroup) { return (count + workgroup - 1u) / workgroup; }

// Integer cell of a coordinate on the hash grid, clamped so far-flung particles stay finite.
int cell_coord(float x, float inv_cell) {
  precise float c = floor(x * inv_cell);
  return int(max(-1048576.0f, min(1048576.0f, c)));
}

uint cell_hash(int cx, int cy, int cz, uint table_size) {
  uint h = uint(cx) * 73856093u ^ uint(cy) * 19349663u ^ uint(cz) * 83492791u;
  return h & (table_size - 1u);
}

#endif
