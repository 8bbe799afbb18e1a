// A grid of spheres for neighbour queries: overlaps while particles are being placed (a random
// fill tries ten or more places per sphere, so this is where a million-sphere fill spends its
// time), and the touching grains of a heap (measure/heap_grains.h).
// The cells are one dense array over a box, the region being filled: a cell is found by
// arithmetic. A sphere no wider than a cell is entered once, in the cell of its centre; a
// larger one (a cabbage's core among its veins) in every cell its bounding box touches. A query
// looks at the cells within its radius plus half a cell of its centre, which holds every centre
// of a small sphere it can touch and a cell shared with every large one. Spheres and queries
// that reach beyond the box use its border cells, so nothing is missed outside it either.
#pragma once
#include <cstdint>
#include <vector>

#include "util/math.h"

namespace repose {

class SphereGrid {
 public:
  // cell_size: about the diameter of the spheres queried most often; [lo, hi]: where the
  // queries are; expected: about how many spheres will be inserted. The cells grow beyond
  // cell_size when the box would need more than 4 per expected sphere (a sparse fill of a big
  // region), which only makes the cells fuller.
  SphereGrid(double cell_size, const Vec3d& lo, const Vec3d& hi, size_t expected);

  // Adds a sphere; its id is the number of spheres added before it.
  void insert(const Vec3d& centre, double radius);

  // Id of the first-found stored sphere that overlaps the given one (centre distance strictly
  // less than the sum of the radii: touching is allowed), or -1. Cells are visited in memory
  // order (z, then y, then x), a cell's spheres newest first.
  int find_overlap(const Vec3d& centre, double radius) const;

  // Calls visit(id, x, y, z, radius) for the spheres stored in the cells within reach plus half a
  // cell of `centre` (every sphere up to half a cell wide whose centre is within reach of it, and
  // every larger one that can reach that far, possibly more than once), in find_overlap's order,
  // until visit returns true; returns whether it did.
  template <class Visit>
  bool visit_near(const Vec3d& centre, double reach, Visit&& visit) const {
    CellRange range = cells_of(centre, reach + small_radius_);
    for (int64_t z = range.lo[2]; z <= range.hi[2]; ++z)
      for (int64_t y = range.lo[1]; y <= range.hi[1]; ++y)
        for (int64_t x = range.lo[0]; x <= range.hi[0]; ++x)
          for (int e = heads_[cell_index(x, y, z)]; e >= 0; e = entries_[size_t(e)].next) {
            const Entry& other = entries_[size_t(e)];
            if (visit(other.sphere, other.x, other.y, other.z, other.radius)) return true;
          }
    return false;
  }

  size_t size() const { return size_t(count_); }

 private:
  struct CellRange { int64_t lo[3], hi[3]; };
  // A sphere's membership of one cell, with its centre and radius at hand (one memory read).
  struct Entry {
    double x, y, z, radius;
    int sphere;
    int next;  // the cell's next older entry, -1 at the end
  };

  CellRange cells_of(const Vec3d& centre, double reach) const;
  size_t cell_index(int64_t x, int64_t y, int64_t z) const {
    return size_t((z * dims_[1] + y) * dims_[0] + x);
  }

  double cell_size_;
  double small_radius_;  // spheres up to this radius are entered by their centre alone
  Vec3d origin_{};
  int64_t dims_[3] = {1, 1, 1};
  int count_ = 0;
  std::vector<int> heads_;  // per cell: its newest entry, -1 when empty
  std::vector<Entry> entries_;
};

}  // namespace repose
