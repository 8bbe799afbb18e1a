// The silhouette area of a cluster of spheres seen along one axis (the union of their discs),
// for air drag on clump bodies: one number per principal axis, measured by rasterising the discs
// on a fine grid (each cell counted once, so overlaps are not double counted).
#pragma once
#include <array>
#include <vector>

namespace repose {

// Areas (m^2) of the union of discs seen along x, y and z of the frame the centres are given in.
// `cells` sets the grid: that many cells across the cluster's widest extent.
std::array<double, 3> projected_areas(const std::vector<std::array<double, 3>>& centres,
                                      const std::vector<double>& radii, int cells = 512);

}  // namespace repose
