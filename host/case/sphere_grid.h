// A hash grid of spheres for overlap queries while particles are being placed. Each sphere is
// entered in every cell its bounding box touches, so two overlapping spheres always share a
// cell whatever their sizes, and a query looks only at the cells of its own bounding box.
#pragma once
#include <cstdint>
#include <vector>

#include "case/case_spec.h"

namespace repose {

class SphereGrid {
 public:
  // cell_size: about the diameter of the spheres queried most often.
  explicit SphereGrid(double cell_size);

  // Adds a sphere; its id is the number of spheres added before it.
  void insert(const Vec3d& centre, double radius);

  // Id of the first-found stored sphere that overlaps the given one (centre distance strictly
  // less than the sum of the radii: touching is allowed), or -1.
  int find_overlap(const Vec3d& centre, double radius) const;

  size_t size() const { return centres_.size(); }

 private:
  struct CellRange { int64_t lo[3], hi[3]; };
  struct Slot { int64_t x, y, z; int head; };  // head < 0: empty slot
  struct Entry { int sphere; int next; };      // a sphere's membership of one cell

  CellRange cells_of(const Vec3d& centre, double radius) const;
  size_t slot_of(int64_t x, int64_t y, int64_t z) const;  // existing or empty slot
  void grow();

  double cell_size_;
  std::vector<Vec3d> centres_;
  std::vector<double> radii_;
  std::vector<Slot> slots_;  // open addressing, power-of-two size
  size_t used_slots_ = 0;
  std::vector<Entry> entries_;
};

}  // namespace repose
