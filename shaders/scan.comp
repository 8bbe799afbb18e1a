#version 450
// In-place exclusive prefix sum of one counter array by a single workgroup, chunk by chunk;
// the total lands at [count]. Integer sums: any order gives the same result, so the CPU twin
// is a plain loop.
#define REPOSE_SCAN_PUSH
#include "kernels/glsl_prelude.glsl"
layout(push_constant) uniform ScanBlock { ScanPush SP; };

shared uint partial[kScanWorkgroup];

uint load_count(uint k) {
  if (SP.target == kScanCells) return B_cell_start[k];
  if (SP.target == kScanRows) return B_row_start[k];
  return B_trans_start[k];
}

void store_start(uint k, uint v) {
  if (SP.target == kScanCells) B_cell_start[k] = v;
  else if (SP.target == kScanRows) B_row_start[k] = v;
  else B_trans_start[k] = v;
}

void main() {
  uint t = gl_LocalInvocationID.x;
  uint carry = 0u;
  for (uint base = 0u; base < SP.count; base += 4u * kScanWorkgroup) {
    uint v[4];
    uint before[4];
    uint sum = 0u;
    for (uint q = 0u; q < 4u; ++q) {
      uint idx = base + 4u * t + q;
      v[q] = idx < SP.count ? load_count(idx) : 0u;
      before[q] = sum;
      sum += v[q];
    }
    partial[t] = sum;
    barrier();
    for (uint off = 1u; off < kScanWorkgroup; off <<= 1u) {
      uint add = t >= off ? partial[t - off] : 0u;
      barrier();
      partial[t] += add;
      barrier();
    }
    uint exclusive = partial[t] - sum;
    uint chunk_total = partial[kScanWorkgroup - 1u];
    for (uint q = 0u; q < 4u; ++q) {
      uint idx = base + 4u * t + q;
      if (idx < SP.count) store_start(idx, carry + exclusive + before[q]);
    }
    carry += chunk_total;
    barrier();
  }
  if (t == 0u) store_start(SP.count, carry);
}
