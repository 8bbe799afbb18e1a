#include "geometry/sphere_grid.h"

#include <algorithm>
#include <cmath>

namespace repose {

SphereGrid::SphereGrid(double cell_size, const Vec3d& lo, const Vec3d& hi, size_t expected) : origin_(lo) {
  double extent[3];
  for (int axis = 0; axis < 3; ++axis) extent[axis] = std::max(0.0, hi[axis] - lo[axis]);
  // At most 4 cells per expected sphere (and 2^12 in any case); each growth by 2^(1/3) halves
  // the count.
  double most = std::max(4096.0, 4.0 * double(expected));
  cell_size_ = cell_size;
  auto cells = [&] {
    double total = 1;
    for (double e : extent) total *= std::floor(e / cell_size_) + 1;
    return total;
  };
  while (cells() > most) cell_size_ *= 1.2599210498948732;
  small_radius_ = 0.5 * cell_size_;
  for (int axis = 0; axis < 3; ++axis) dims_[axis] = int64_t(std::floor(extent[axis] / cell_size_)) + 1;
  heads_.assign(size_t(dims_[0] * dims_[1] * dims_[2]), -1);
  entries_.reserve(expected);
}

SphereGrid::CellRange SphereGrid::cells_of(const Vec3d& centre, double reach) const {
  CellRange range;
  for (int axis = 0; axis < 3; ++axis) {
    auto cell = [&](double x) {
      double c = std::floor((x - origin_[axis]) / cell_size_);
      return int64_t(std::clamp(c, 0.0, double(dims_[axis] - 1)));  // beyond the box: its border cells
    };
    range.lo[axis] = cell(centre[axis] - reach);
    range.hi[axis] = cell(centre[axis] + reach);
  }
  return range;
}

void SphereGrid::insert(const Vec3d& centre, double radius) {
  int id = count_++;
  CellRange range = cells_of(centre, radius <= small_radius_ ? 0.0 : radius);
  for (int64_t x = range.lo[0]; x <= range.hi[0]; ++x)
    for (int64_t y = range.lo[1]; y <= range.hi[1]; ++y)
      for (int64_t z = range.lo[2]; z <= range.hi[2]; ++z) {
        int& head = heads_[cell_index(x, y, z)];
        entries_.push_back(Entry{centre[0], centre[1], centre[2], radius, id, head});
        head = int(entries_.size() - 1);
      }
}

int SphereGrid::find_overlap(const Vec3d& centre, double radius) const {
  int found = -1;
  visit_near(centre, radius, [&](int sphere, double x, double y, double z, double r) {
    double dx = centre[0] - x, dy = centre[1] - y, dz = centre[2] - z;
    double reach = radius + r;
    if (!(dx * dx + dy * dy + dz * dz < reach * reach)) return false;
    found = sphere;
    return true;
  });
  return found;
}

}  // namespace repose
