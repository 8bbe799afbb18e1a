#include "case/sphere_grid.h"

#include <cmath>

namespace repose {

SphereGrid::SphereGrid(double cell_size) : cell_size_(cell_size), slots_(1024, Slot{0, 0, 0, -1}) {}

SphereGrid::CellRange SphereGrid::cells_of(const Vec3d& centre, double radius) const {
  CellRange range;
  for (int axis = 0; axis < 3; ++axis) {
    range.lo[axis] = int64_t(std::floor((centre[axis] - radius) / cell_size_));
    range.hi[axis] = int64_t(std::floor((centre[axis] + radius) / cell_size_));
  }
  return range;
}

size_t SphereGrid::slot_of(int64_t x, int64_t y, int64_t z) const {
  // splitmix-style mixing of the three cell coordinates; linear probing.
  uint64_t h = uint64_t(x) * 0x9E3779B97F4A7C15ull;
  h ^= uint64_t(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= uint64_t(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  h ^= h >> 31;
  size_t mask = slots_.size() - 1;
  for (size_t i = size_t(h) & mask;; i = (i + 1) & mask) {
    const Slot& slot = slots_[i];
    if (slot.head < 0 || (slot.x == x && slot.y == y && slot.z == z)) return i;
  }
}

void SphereGrid::grow() {
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(old.size() * 2, Slot{0, 0, 0, -1});
  for (const Slot& slot : old)
    if (slot.head >= 0) slots_[slot_of(slot.x, slot.y, slot.z)] = slot;
}

void SphereGrid::insert(const Vec3d& centre, double radius) {
  int id = int(centres_.size());
  centres_.push_back(centre);
  radii_.push_back(radius);
  CellRange range = cells_of(centre, radius);
  for (int64_t x = range.lo[0]; x <= range.hi[0]; ++x)
    for (int64_t y = range.lo[1]; y <= range.hi[1]; ++y)
      for (int64_t z = range.lo[2]; z <= range.hi[2]; ++z) {
        if (2 * (used_slots_ + 1) > slots_.size()) grow();
        Slot& slot = slots_[slot_of(x, y, z)];
        if (slot.head < 0) {
          slot = Slot{x, y, z, -1};
          ++used_slots_;
        }
        entries_.push_back(Entry{id, slot.head});
        slot.head = int(entries_.size() - 1);
      }
}

int SphereGrid::find_overlap(const Vec3d& centre, double radius) const {
  CellRange range = cells_of(centre, radius);
  for (int64_t x = range.lo[0]; x <= range.hi[0]; ++x)
    for (int64_t y = range.lo[1]; y <= range.hi[1]; ++y)
      for (int64_t z = range.lo[2]; z <= range.hi[2]; ++z) {
        const Slot& slot = slots_[slot_of(x, y, z)];
        for (int e = slot.head; e >= 0; e = entries_[e].next) {
          int other = entries_[e].sphere;
          double dx = centre[0] - centres_[other][0];
          double dy = centre[1] - centres_[other][1];
          double dz = centre[2] - centres_[other][2];
          double reach = radius + radii_[other];
          if (dx * dx + dy * dy + dz * dz < reach * reach) return other;
        }
      }
  return -1;
}

}  // namespace repose
