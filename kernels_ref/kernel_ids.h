// The kernels of one simulation step, named as their shaders (shaders/NAME.comp). A step is a
// list of dispatches of these; the Vulkan backend records it, the CPU twin interprets it.
#pragma once
#include <cstdint>

namespace repose {

enum class KernelId : uint32_t {
  KickDrift, GatherKick, RebuildArgs, SaveOldRows, SaveOldContacts, ClearBuckets, BucketCount,
  BucketScatter, BucketSort, ContactCount, RowsScanned, ContactFill, TransposeCount,
  TransposeFill, TransposeSort, ContactForces, ContactRows, Scan, WallReduce, GatherLean,
  BodyKickDrift, BodyPlace, BodyGatherKick, Count
};

inline const char* kernel_shader_name(KernelId k) {
  static const char* names[] = {
      "kick_drift",     "gather_kick",     "rebuild_args",   "save_old_rows",
      "save_old_contacts", "clear_buckets", "bucket_count",  "bucket_scatter",
      "bucket_sort",    "contact_count",   "rows_scanned",   "contact_fill",
      "transpose_count", "transpose_fill", "transpose_sort", "contact_forces",
      "contact_rows",   "scan",            "wall_reduce",    "gather_lean",
      "body_kick_drift", "body_place",     "body_gather_kick"};
  static_assert(sizeof(names) / sizeof(names[0]) == static_cast<int>(KernelId::Count));
  return names[static_cast<int>(k)];
}

}  // namespace repose
