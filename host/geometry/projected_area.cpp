#include "geometry/projected_area.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "util/math.h"

namespace repose {

namespace {

// Union area of discs (u, v, r) by counting grid cells whose centre lies in at least one disc.
double union_of_discs(const std::vector<std::array<double, 3>>& discs, int cells) {
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (const auto& d : discs) {
    lo_u = std::min(lo_u, d[0] - d[2]);
    hi_u = std::max(hi_u, d[0] + d[2]);
    lo_v = std::min(lo_v, d[1] - d[2]);
    hi_v = std::max(hi_v, d[1] + d[2]);
  }
  double h = std::max(hi_u - lo_u, hi_v - lo_v) / cells;
  int nu = int(std::ceil((hi_u - lo_u) / h)) + 1, nv = int(std::ceil((hi_v - lo_v) / h)) + 1;
  std::vector<char> inside(size_t(nu) * size_t(nv), 0);
  for (const auto& d : discs) {
    // Only the cells of the disc's bounding box are visited.
    int u0 = std::max(0, int(std::floor((d[0] - d[2] - lo_u) / h))), u1 = std::min(nu - 1, int(std::ceil((d[0] + d[2] - lo_u) / h)));
    int v0 = std::max(0, int(std::floor((d[1] - d[2] - lo_v) / h))), v1 = std::min(nv - 1, int(std::ceil((d[1] + d[2] - lo_v) / h)));
    double r2 = d[2] * d[2];
    for (int i = u0; i <= u1; ++i) {
      double du = lo_u + (i + 0.5) * h - d[0];
      for (int j = v0; j <= v1; ++j) {
        double dv = lo_v + (j + 0.5) * h - d[1];
        if (du * du + dv * dv <= r2) inside[size_t(i) * size_t(nv) + size_t(j)] = 1;
      }
    }
  }
  size_t count = size_t(std::count(inside.begin(), inside.end(), char(1)));
  return double(count) * h * h;
}

}  // namespace

std::array<double, 3> projected_areas(const std::vector<std::array<double, 3>>& centres,
                                      const std::vector<double>& radii, int cells) {
  if (centres.empty() || centres.size() != radii.size())
    throw std::invalid_argument("projected_areas: one radius per centre, at least one sphere");
  if (centres.size() == 1) {  // exact for a lone sphere
    double a = kPi * radii[0] * radii[0];
    return {a, a, a};
  }
  std::array<double, 3> out{};
  for (int axis = 0; axis < 3; ++axis) {
    int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the plane across the viewing axis
    std::vector<std::array<double, 3>> discs;
    for (size_t k = 0; k < centres.size(); ++k) discs.push_back({centres[k][a], centres[k][b], radii[k]});
    out[size_t(axis)] = union_of_discs(discs, cells);
  }
  return out;
}

}  // namespace repose
