// Math helpers shared by every kernel, GLSL and C++ alike. Each is written out left to right with
// `precise` temporaries so that lavapipe and g++ evaluate the same operations in the same order.
#ifndef REPOSE_KERNELS_COMMON_H
#define REPOSE_KERNELS_COMMON_H

#include "kernels/vector3.h"

vec3 xyz(vec4 v) { return vec3(v.x, v.y, v.z); }

// Groups of `workgroup` invocations needed to cover `count` items.
uint groups_for(uint count, uint workgroup) { return (count + workgroup - 1u) / workgroup; }

// Integer cell of a coordinate on the hash grid, clamped so far-flung particles stay finite.
int cell_coord(float x, float inv_cell) {
  precise float c = floor(x * inv_cell);
  return int(max(-1048576.0f, min(1048576.0f, c)));
}

// A row of cells along x takes consecutive buckets (its start hashed from y and z), so a walk's
// three cells along x, and the next sphere's, share cache lines in the bucket starts and the
// sorted slots (the walk's loads were its cost; a hash of all three coordinates scattered them).
uint cell_hash(int cx, int cy, int cz, uint table_size) {
  uint h = uint(cx) + (uint(cy) * 19349663u ^ uint(cz) * 83492791u);
  return h & (table_size - 1u);
}

// Particles sit in storage slots (repose_shared.h): the global id of the particle in slot i, and
// the slot of global id g.
uint global_id(uint i) { return B_ids[i]; }
uint slot_of(uint g) { return B_ids[PC.n_particles + g]; }
// A partner's place in a row's order: its global id, or after every particle N + w for wall w.
uint partner_key(uint p) { return p < PC.n_particles ? global_id(p) : p; }

// True when list partner p is a wall of named wall `group` (WallState.info.w; every row of a
// wall holds the same).
bool partner_in_wall_group(uint p, uint group) {
  return p >= PC.n_particles && B_walls[p - PC.n_particles].info.w == group;
}

// The force f on named wall w this step (wall_reduce). With PC.wall_sums also, after the walls' forces,
// its running sum (times dt: the impulse) and the largest force since the sums began (xyz, w its
// squared length); 2 begins them anew with this step.
void store_wall_force(uint w, vec3 f) {
  B_wall_force[w] = vec4(f.x, f.y, f.z, 0.0f);
  if (PC.wall_sums == 0u) return;
  uint n = PC.n_wall_groups;
  bool fresh = PC.wall_sums == 2u;
  vec3 before = fresh ? vec3(0.0f) : xyz(B_wall_force[n + w]);
  precise vec3 sum = before + f;
  B_wall_force[n + w] = vec4(sum.x, sum.y, sum.z, 0.0f);
  precise float m = dot3(f, f);
  if (fresh || m > B_wall_force[2u * n + w].w) B_wall_force[2u * n + w] = vec4(f.x, f.y, f.z, m);
}

#endif
