// The kernels of one simulation step, in one list: the ids and names below, the CPU twin's
// dispatch (run_kernel, cpu_kernels.cpp) and the GLSL entry points shaders/NAME.comp that CMake
// writes at configure time (CMakeLists.txt reads this list) all follow from it. A step is a list
// of dispatches of these; the Vulkan backend records it, the CPU twin interprets it. Columns:
//   Id (KernelId::Id), name (the kernel function k_name in shaders/kernels/, its shader), kind:
//   Each  one invocation per item: invocation_index() on the device, the thread pool in the twin;
//   Once  one invocation decides (a control kernel): invocation 0 only, on one thread;
//   Own   a shader and a twin of its own (shaders/name.comp, run_scan/run_wall_reduce).
#pragma once
#include <cstdint>

// One row a line (CMakeLists.txt reads the rows by this pattern).
#define REPOSE_KERNELS(X) \
  X(KickDrift, kick_drift, Each) \
  X(GatherKick, gather_kick, Each) \
  X(RebuildArgs, rebuild_args, Once) \
  X(SaveOldRows, save_old_rows, Each) \
  X(SaveOldContacts, save_old_contacts, Each) \
  X(ClearBuckets, clear_buckets, Each) \
  X(BucketCount, bucket_count, Each) \
  X(BucketScatter, bucket_scatter, Each) \
  X(BucketSort, bucket_sort, Each) \
  X(PartPlace, part_place, Each) \
  X(PartNear, part_near, Each) \
  X(ContactCount, contact_count, Each) \
  X(RowsScanned, rows_scanned, Once) \
  X(ContactFill, contact_fill, Each) \
  X(TransposeCount, transpose_count, Each) \
  X(TransposeFill, transpose_fill, Each) \
  X(TransposeSort, transpose_sort, Each) \
  X(ClearTouches, clear_touches, Each) \
  X(TouchCount, touch_count, Each) \
  X(ContactForces, contact_forces, Each) \
  X(ContactRows, contact_rows, Each) \
  X(Scan, scan, Own) \
  X(WallReduce, wall_reduce, Own) \
  X(GatherLean, gather_lean, Each) \
  X(BodyKickDrift, body_kick_drift, Each) \
  X(BodyPlace, body_place, Each) \
  X(BodyGatherKick, body_gather_kick, Each)

namespace repose {

enum class KernelId : uint32_t {
#define REPOSE_KERNEL_ID(Id, name, kind) Id,
  REPOSE_KERNELS(REPOSE_KERNEL_ID)
#undef REPOSE_KERNEL_ID
  Count
};

inline const char* kernel_shader_name(KernelId k) {
  static const char* const names[] = {
#define REPOSE_KERNEL_NAME(Id, name, kind) #name,
      REPOSE_KERNELS(REPOSE_KERNEL_NAME)
#undef REPOSE_KERNEL_NAME
  };
  return names[static_cast<uint32_t>(k)];
}

}  // namespace repose
