// Volume, centroid and second moments of the UNION of a set of spheres (overlaps counted once).
//
// Method (deterministic, no random sampling): lines are cast along the bounding box's longest
// axis through a regular 2D grid over the other two axes. Along one line the union of the
// spheres' chords is computed exactly (interval merge), and so are the line integrals of 1, z and
// z^2. The 2D integral of those line integrals uses 3x3 Gauss-Legendre points per cell; cells
// that a sphere's silhouette circle crosses or passes within one cell size of (where the
// integrand has its square-root edge) are split into quadrants recursively, refine_depth times,
// and the finest edge cells take 2x2 Gauss points.
//
// Accuracy, measured by tests/geometry/test_clump.cpp against closed forms (a sphere, two
// overlapping equal and unequal spheres, chains with and without triple overlaps, lines along
// and across the overlaps), worst relative error of volume / of any inertia entry:
//   refine_depth 4 (default): 1.6e-5 / 2.0e-5;  5: 5.7e-6 / 8.2e-6;  6: 1.4e-6 / 2.2e-6.
// Each level costs about 2.5x the time; at the default a cabbage (203 spheres) takes ~0.5 s and
// the 720-sphere stalk ~0.6 s on one core. The error comes from the square-root edges and
// decreases like (cell size)^1.5. The result does not depend on the order of the spheres beyond
// rounding.
#pragma once
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "geometry/sphere.h"

namespace repose {

struct UnionIntegration {
  double cells_per_min_radius = 4.0;  // grid cell = smallest radius / this ...
  int max_cells_per_side = 1024;      // ... unless the grid would exceed this many cells a side
  int refine_depth = 4;  // edge cells are split until r / (cells_per_min_radius * 2^depth)
  int line_axis = -1;    // 0, 1, 2: cast lines along x, y, z; -1: along the longest extent
};

struct UnionMoments {
  double volume = 0.0;                   // m^3
  glm::dvec3 centroid{0.0};              // m
  glm::dmat3 central_second_moment{0.0};  // integral of (x-c)(x-c)^T dV over the union, m^5
};

// Throws std::invalid_argument for an empty list or a non-positive / non-finite radius.
UnionMoments union_moments(const std::vector<Sphere>& spheres, const UnionIntegration& options = {});

}  // namespace repose
