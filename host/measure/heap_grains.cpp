#include "measure/heap_grains.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include "geometry/sphere_grid.h"

namespace repose {

namespace {

bool touching(const Sphere& a, const Sphere& b) {
  glm::dvec3 d = a.centre - b.centre;
  double reach = a.radius + b.radius + kTouchGap * std::min(a.radius, b.radius);
  return d.x * d.x + d.y * d.y + d.z * d.z <= reach * reach;
}

// The spheres in a grid of cells about a diameter wide (geometry/sphere_grid.h), ids in order.
SphereGrid grid_of(const std::vector<Sphere>& spheres) {
  Vec3d lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double radii = 0;
  for (const Sphere& s : spheres) {
    const double c[3] = {s.centre.x, s.centre.y, s.centre.z};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    radii += s.radius;
  }
  SphereGrid grid(std::max(1e-12, 2.0 * radii / double(std::max<size_t>(spheres.size(), 1))), lo, hi, spheres.size());
  for (const Sphere& s : spheres) grid.insert({s.centre.x, s.centre.y, s.centre.z}, s.radius);
  return grid;
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
  SphereGrid grid = grid_of(spheres);
  while (!reached.empty()) {
    uint32_t i = reached.back();
    reached.pop_back();
    const Sphere& s = spheres[i];
    // A sphere touching i has a point within (1 + kTouchGap) r_i of i's centre.
    grid.visit_near({s.centre.x, s.centre.y, s.centre.z}, (1.0 + kTouchGap) * s.radius,
                    [&](int j, double, double, double, double) {
                      if (!resting[size_t(j)] && touching(s, spheres[size_t(j)])) rest(uint32_t(j));
                      return false;
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
