#include "engine/kernel_traffic.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <vector>

#include "engine/buffer_table.h"
#include "engine/run_profile.h"
#include "thread_pool.h"

namespace repose {

namespace {

enum class Per { Particle, Contact, OldContact, Bucket };

// One buffer a kernel touches: per what its elements go, and 1 (read or written) or 2 (both).
struct Access {
  BufferRow row;
  Per per;
  int times;
};

// The buffers of each kernel, from shaders/kernels/neighbour.h, contacts.h and integrate.h. The id
// table (B_ids, 2 x 4 B per particle) counts once per particle: the sphere kernels read only its
// first half, each slot's global id (global_id, partner_key in shaders/kernels/common.h), where a
// walk, a row or a bucket is ordered by id; the step's kernels read none.
const std::map<std::string, std::vector<Access>>& kernel_accesses() {
  using P = Per;
  static const std::map<std::string, std::vector<Access>> table = {
      {"kick_drift", {{kRowForce, P::Particle, 1}, {kRowTorque, P::Particle, 1}, {kRowVel, P::Particle, 2},
                      {kRowOmega, P::Particle, 2}, {kRowPos, P::Particle, 2}, {kRowPosAtBuild, P::Particle, 1}}},
      {"contact_forces", {{kRowOwner, P::Contact, 1}, {kRowPartner, P::Contact, 1}, {kRowHistory, P::Contact, 2},
                          {kRowRollingSpring, P::Contact, 2}, {kRowContactForce, P::Contact, 1},
                          {kRowTorqueI, P::Contact, 1}, {kRowTorqueJ, P::Contact, 1}, {kRowPos, P::Particle, 1},
                          {kRowVel, P::Particle, 1}, {kRowOmega, P::Particle, 1}, {kRowMaterial, P::Particle, 1}}},
      {"gather_kick", {{kRowRowStart, P::Particle, 1}, {kRowTransStart, P::Particle, 1}, {kRowTransList, P::Contact, 1},
                       {kRowContactForce, P::Contact, 1}, {kRowTorqueI, P::Contact, 1}, {kRowTorqueJ, P::Contact, 1},
                       {kRowForce, P::Particle, 1}, {kRowTorque, P::Particle, 1}, {kRowVel, P::Particle, 2},
                       {kRowOmega, P::Particle, 2}, {kRowPos, P::Particle, 2}, {kRowPosAtBuild, P::Particle, 1}}},
      {"gather_lean", {{kRowRowStart, P::Particle, 1}, {kRowTransStart, P::Particle, 1}, {kRowTransList, P::Contact, 1},
                       {kRowOwner, P::Contact, 1}, {kRowPartner, P::Contact, 1}, {kRowContactForce, P::Contact, 1},
                       {kRowTorqueI, P::Contact, 1}, {kRowForce, P::Particle, 1}, {kRowTorque, P::Particle, 1},
                       {kRowVel, P::Particle, 2}, {kRowOmega, P::Particle, 2}, {kRowPos, P::Particle, 2},
                       {kRowPosAtBuild, P::Particle, 1}}},
      // A rebuild: save the old list, bin the particles, count and fill the rows, transpose them.
      {"save_old_rows", {{kRowRowStart, P::Particle, 1}, {kRowOldRowStart, P::Particle, 1}}},
      {"save_old_contacts", {{kRowPartner, P::OldContact, 1}, {kRowHistory, P::OldContact, 1},
                             {kRowOldPartner, P::OldContact, 1}, {kRowOldHistory, P::OldContact, 1}}},
      {"clear_buckets", {{kRowCellStart, P::Bucket, 1}, {kRowCellFill, P::Bucket, 1}}},
      {"bucket_count", {{kRowPos, P::Particle, 1}, {kRowPosAtBuild, P::Particle, 1}, {kRowCellOf, P::Particle, 1},
                        {kRowCellStart, P::Bucket, 2}}},
      {"bucket_scatter", {{kRowCellOf, P::Particle, 1}, {kRowCellStart, P::Bucket, 1}, {kRowCellFill, P::Bucket, 2},
                          {kRowSorted, P::Particle, 1}}},
      {"bucket_sort", {{kRowCellStart, P::Bucket, 1}, {kRowSorted, P::Particle, 2}, {kRowIds, P::Particle, 1}}},
      {"contact_count", {{kRowPos, P::Particle, 1}, {kRowVel, P::Particle, 1}, {kRowCellStart, P::Bucket, 1},
                         {kRowSorted, P::Particle, 1}, {kRowIds, P::Particle, 1}, {kRowCandidates, P::Contact, 1},
                         {kRowRowStart, P::Particle, 1}, {kRowTransStart, P::Particle, 1},
                         {kRowTransFill, P::Particle, 1}}},
      {"contact_fill", {{kRowRowStart, P::Particle, 1}, {kRowOldRowStart, P::Particle, 1},
                        {kRowCandidates, P::Contact, 1}, {kRowIds, P::Particle, 1}, {kRowPartner, P::Contact, 1},
                        {kRowOwner, P::Contact, 1}, {kRowHistory, P::Contact, 1},
                        {kRowOldPartner, P::OldContact, 1}, {kRowOldHistory, P::OldContact, 1}}},
      {"transpose_count", {{kRowPartner, P::Contact, 1}, {kRowTransStart, P::Particle, 2}}},
      {"transpose_fill", {{kRowPartner, P::Contact, 1}, {kRowTransStart, P::Particle, 1},
                          {kRowTransFill, P::Particle, 2}, {kRowTransList, P::Contact, 1}}},
      {"transpose_sort", {{kRowTransStart, P::Particle, 1}, {kRowTransList, P::Contact, 2}, {kRowOwner, P::Contact, 1},
                          {kRowIds, P::Particle, 1}}},
      // The three scans of a rebuild (buckets, rows, transposed rows), in place.
      {"scan", {{kRowCellStart, P::Bucket, 2}, {kRowRowStart, P::Particle, 2}, {kRowTransStart, P::Particle, 2}}},
  };
  return table;
}

}  // namespace

double kernel_min_bytes(const std::string& kernel, const Layout& layout, const TrafficCounts& n) {
  auto it = kernel_accesses().find(kernel);
  if (it == kernel_accesses().end()) return 0;
  double bytes = 0;
  for (const Access& a : it->second) {
    const BufferSpec& b = kBufferTable[a.row];
    if (buffer_elements(b, layout) == 0) continue;  // a buffer this layout has not (lean, no springs)
    double count = a.per == Per::Particle ? n.particles
                 : a.per == Per::Contact  ? n.contacts
                 : a.per == Per::OldContact ? n.old_contacts
                                            : n.buckets;
    bytes += count * double(b.element_bytes) * a.times;
  }
  return bytes;
}

bool rebuild_kernel(const std::string& kernel) { return std::strcmp(kernel_stage(kernel), "neighbours") == 0; }

CopyMeter::CopyMeter(size_t bytes, ThreadPool& pool)
    : from_(std::max<size_t>(bytes / sizeof(double), 1024), 1.0), to_(from_.size(), 0.0), pool_(pool) {}

double CopyMeter::bandwidth(int passes) {
  double best = 0;
  for (int pass = 0; pass < passes; ++pass) {
    auto t0 = std::chrono::steady_clock::now();
    pool_.parallel_for(from_.size(), [&](uint64_t begin, uint64_t end) {
      std::memcpy(to_.data() + begin, from_.data() + begin, (end - begin) * sizeof(double));
    });
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::max(best, 2.0 * double(from_.size() * sizeof(double)) / seconds);
  }
  return best;
}

}  // namespace repose
