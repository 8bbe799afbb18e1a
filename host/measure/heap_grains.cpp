#include "measure/heap_grains.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace repose {

namespace {

// Spheres binned in cubes at least as wide as the farthest touch, so that a sphere's touching
// spheres lie in its cube and the 26 around it.
class SphereGrid {
 public:
  explicit SphereGrid(const std::vector<Sphere>& spheres) {
    double largest = 0;
    for (const Sphere& s : spheres) largest = std::max(largest, s.radius);
    cube_ = std::max(1e-12, (2.0 + kTouchGap) * largest);
    for (uint32_t i = 0; i < spheres.size(); ++i) cells_[key(cell_of(spheres[i].centre))].push_back(i);
  }
  template <class Visit>
  void around(const glm::dvec3& centre, Visit&& visit) const {
    Cell c = cell_of(centre);
    for (int64_t dz = -1; dz <= 1; ++dz)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dx = -1; dx <= 1; ++dx) {
          auto found = cells_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (found != cells_.end())
            for (uint32_t j : found->second) visit(j);
        }
  }

 private:
  using Cell = std::array<int64_t, 3>;
  Cell cell_of(const glm::dvec3& p) const {
    return {int64_t(std::floor(p.x / cube_)), int64_t(std::floor(p.y / cube_)), int64_t(std::floor(p.z / cube_))};
  }
  static uint64_t key(const Cell& c) {  // 21 bits a coordinate: +-10^6 cubes
    auto bits = [](int64_t v) { return uint64_t(v + (int64_t(1) << 20)) & ((uint64_t(1) << 21) - 1); };
    return bits(c[0]) | bits(c[1]) << 21 | bits(c[2]) << 42;
  }
  double cube_ = 1;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

bool touching(const Sphere& a, const Sphere& b) {
  glm::dvec3 d = a.centre - b.centre;
  double reach = a.radius + b.radius + kTouchGap * std::min(a.radius, b.radius);
  return d.x * d.x + d.y * d.y + d.z * d.z <= reach * reach;
}

}  // namespace

std::vector<bool> resting_on_floor(const std::vector<Sphere>& spheres, double floor_z,
                                   const std::vector<uint32_t>& bodies) {
  if (!bodies.empty() && bodies.size() != spheres.size())
    throw std::invalid_argument("resting_on_floor: one body per sphere, or none");
  std::unordered_map<uint32_t, std::vector<uint32_t>> members;  // a body's spheres
  for (uint32_t i = 0; i < bodies.size(); ++i) members[bodies[i]].push_back(i);
  std::vector<bool> resting(spheres.size(), false);
  std::vector<uint32_t> reached;  // resting spheres whose neighbours are still to be visited
  auto rest = [&](uint32_t i) {
    if (resting[i]) return;
    if (bodies.empty()) {
      resting[i] = true;
      reached.push_back(i);
      return;
    }
    for (uint32_t k : members[bodies[i]]) {
      resting[k] = true;
      reached.push_back(k);
    }
  };
  for (uint32_t i = 0; i < spheres.size(); ++i)
    if (spheres[i].centre.z - spheres[i].radius <= floor_z + kFloorGap * spheres[i].radius) rest(i);
  SphereGrid grid(spheres);
  while (!reached.empty()) {
    uint32_t i = reached.back();
    reached.pop_back();
    grid.around(spheres[i].centre, [&](uint32_t j) {
      if (!resting[j] && touching(spheres[i], spheres[j])) rest(j);
    });
  }
  return resting;
}

size_t keep_resting(std::vector<Sphere>& spheres, double floor_z, const std::vector<uint32_t>& bodies) {
  std::vector<bool> resting = resting_on_floor(spheres, floor_z, bodies);
  size_t kept = 0;
  for (size_t i = 0; i < spheres.size(); ++i)
    if (resting[i]) spheres[kept++] = spheres[i];
  size_t apart = spheres.size() - kept;
  spheres.resize(kept);
  return apart;
}

}  // namespace repose
