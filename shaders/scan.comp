#version 450
// In-place exclusive prefix sum of one counter array; the total lands at [count]. Either one
// workgroup walks the array a block at a time (kScanPassWhole: few blocks), or a reduce-then-scan
// takes the whole device in three dispatches: every workgroup sums its block (kScanPassSums), one
// workgroup scans those sums (kScanPassOffsets), every workgroup scans its block from its offset
// (kScanPassBlocks). No workgroup waits for another (Vulkan promises no forward progress between
// them), and nothing depends on the subgroup size. Integer sums: any grouping gives the same
// result, and the CPU twin (run_scan) does the same passes as plain loops.
#define REPOSE_SCAN_PUSH
#include "kernels/glsl_prelude.glsl"
layout(push_constant) uniform ScanBlock { ScanPush SP; };

shared uint partial[kScanWorkgroup];

uint load_count(uint target, uint k) {
  if (target == kScanCells) return B_cell_start[k];
  if (target == kScanRows) return B_row_start[k];
  if (target == kScanTransposed) return B_trans_start[k];
  return B_scan_blocks[k];
}

void store_start(uint target, uint k, uint v) {
  if (target == kScanCells) B_cell_start[k] = v;
  else if (target == kScanRows) B_row_start[k] = v;
  else if (target == kScanTransposed) B_trans_start[k] = v;
  else B_scan_blocks[k] = v;
}

// Scans the block of entries [base, base + kScanBlock) below `count` from `carry` (each
// invocation its kScanPerThread consecutive entries) and returns the block's sum. Called by the
// whole workgroup.
uint scan_block(uint target, uint count, uint base, uint carry) {
  uint t = gl_LocalInvocationID.x;
  uint v[kScanPerThread];
  uint before[kScanPerThread];
  uint sum = 0u;
  for (uint q = 0u; q < kScanPerThread; ++q) {
    uint idx = base + kScanPerThread * t + q;
    v[q] = idx < count ? load_count(target, idx) : 0u;
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
  uint block_total = partial[kScanWorkgroup - 1u];
  for (uint q = 0u; q < kScanPerThread; ++q) {
    uint idx = base + kScanPerThread * t + q;
    if (idx < count) store_start(target, idx, carry + exclusive + before[q]);
  }
  barrier();  // partial is read above before the next block writes it
  return block_total;
}

// The sum of the block at `base`, read with neighbouring invocations on neighbouring entries.
uint sum_block(uint base) {
  uint t = gl_LocalInvocationID.x;
  uint sum = 0u;
  for (uint q = 0u; q < kScanPerThread; ++q) {
    uint idx = base + q * kScanWorkgroup + t;
    if (idx < SP.count) sum += load_count(SP.target, idx);
  }
  partial[t] = sum;
  barrier();
  for (uint half_size = kScanWorkgroup / 2u; half_size > 0u; half_size >>= 1u) {
    if (t < half_size) partial[t] += partial[t + half_size];
    barrier();
  }
  return partial[0];
}

// Scans all `count` entries of `target` with this one workgroup; returns the total.
uint scan_all(uint target, uint count) {
  uint carry = 0u;
  for (uint base = 0u; base < count; base += kScanBlock) carry += scan_block(target, count, base, carry);
  return carry;
}

void main() {
  bool first = gl_LocalInvocationID.x == 0u;
  // This workgroup's block, counting across rows of workgroups (dispatch_rows).
  uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint blocks = scan_blocks_for(SP.count);
  if (SP.pass == kScanPassWhole) {
    uint total = scan_all(SP.target, SP.count);
    if (first) store_start(SP.target, SP.count, total);
  } else if (SP.pass == kScanPassOffsets) {
    uint total = scan_all(kScanBlockSums, blocks);  // the total also lands at B_scan_blocks[blocks]
    if (first) {
      store_start(kScanBlockSums, blocks, total);
      store_start(SP.target, SP.count, total);
    }
  } else if (block < blocks) {  // the whole workgroup or none of it: the barriers stay uniform
    if (SP.pass == kScanPassSums) {
      uint sum = sum_block(block * kScanBlock);
      if (first) B_scan_blocks[block] = sum;
    } else {
      scan_block(SP.target, SP.count, block * kScanBlock, B_scan_blocks[block]);
    }
  }
}
