#version 450
// Force on each named wall (a mesh's triangles together, a box's faces each: WallState.info.w):
// one workgroup per named wall sums -F over the contacts with its walls, each thread over every
// 256th particle's row (by global id, not by storage or list slot, so the sum depends on neither
// the storage order nor what else the list holds), then a fixed tree. The CPU twin repeats the
// same order. Its cost is the named walls times the list, not the triangles times the particles.
#include "kernels/glsl_prelude.glsl"
#include "kernels/common.h"

shared float sum_x[kWallReduceWorkgroup];
shared float sum_y[kWallReduceWorkgroup];
shared float sum_z[kWallReduceWorkgroup];

void main() {
  // One workgroup per named wall, in rows of workgroups when there are many (dispatch_rows);
  // a whole group past the last one leaves together, before any barrier.
  uint w = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (w >= PC.n_wall_groups) return;
  uint t = gl_LocalInvocationID.x;
  uint limit = B_control[kCtlContacts];
  precise vec3 acc = vec3(0.0f);
  for (uint g = t; g < PC.n_particles; g += kWallReduceWorkgroup) {
    uint i = slot_of(g);
    uint end = min(B_row_start[i + 1u], limit);
    for (uint c = min(B_row_start[i], limit); c < end; ++c)
      if (partner_in_wall_group(B_partner[c], w)) acc = acc - xyz(B_contact_force[c]);
  }
  sum_x[t] = acc.x;
  sum_y[t] = acc.y;
  sum_z[t] = acc.z;
  barrier();
  for (uint s = kWallReduceWorkgroup / 2u; s > 0u; s >>= 1u) {
    if (t < s) {
      precise float x = sum_x[t] + sum_x[t + s];
      precise float y = sum_y[t] + sum_y[t + s];
      precise float z = sum_z[t] + sum_z[t + s];
      sum_x[t] = x;
      sum_y[t] = y;
      sum_z[t] = z;
    }
    barrier();
  }
  if (t == 0u) store_wall_force(w, vec3(sum_x[0], sum_y[0], sum_z[0]));
}
