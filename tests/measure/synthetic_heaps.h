// Synthetic heaps of known slope, built from spheres, for the angle-measurement tests.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/sphere.h"
#include "util/math.h"

namespace repose::test {

inline double radians(double degrees) { return degrees * kPi / 180.0; }

// Deterministic uniform numbers in [0, 1) (SplitMix64).
inline double uniform(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

// Spheres of radius r whose centres lie on the surface of a cone (apex at height `height` above
// the floor z = 0 at (cx, cy), slope `slope_deg`), rings one radius apart, each ring rotated by
// the golden angle so that no generator lines up. The silhouette is the cone offset by r: its
// slope is exactly slope_deg away from apex and base.
inline std::vector<Sphere> cone_shell(double height, double slope_deg, double r, double cx = 0, double cy = 0) {
  std::vector<Sphere> spheres;
  const double t = std::tan(radians(slope_deg));
  const double base = height / t;
  const int rings = static_cast<int>(std::ceil(base / r));
  for (int k = 0; k <= rings; ++k) {
    const double rho = base * k / rings;
    const int around = std::max(1, static_cast<int>(std::ceil(2 * kPi * rho / r)));
    for (int j = 0; j < around; ++j) {
      const double phi = 2 * kPi * j / around + 2.399963229728653 * k;
      spheres.push_back({{cx + rho * std::cos(phi), cy + rho * std::sin(phi), height - rho * t}, r});
    }
  }
  return spheres;
}

// A rough, filled cone: a random skin of spheres (radii in [0.8, 1.2] r, uniform over the
// surface area) each sunk under the cone surface by a random gap of up to r/2, over a lattice of
// interior spheres. The envelope is bumpy like a real heap's but follows the cone on average.
inline std::vector<Sphere> rough_cone(double height, double slope_deg, double r, uint64_t seed) {
  std::vector<Sphere> spheres;
  const double t = std::tan(radians(slope_deg));
  const double base = height / t;
  const double lift = 1.0 / std::cos(radians(slope_deg));  // vertical depth per unit normal depth
  const double lateral_area = kPi * base * std::hypot(base, height);
  const int skin = static_cast<int>(3.0 * lateral_area / (kPi * r * r));
  for (int i = 0; i < skin; ++i) {
    const double rho = base * std::sqrt(uniform(seed)), phi = 2 * kPi * uniform(seed);
    const double radius = r * (0.8 + 0.4 * uniform(seed));
    const double gap = 0.5 * r * uniform(seed);
    const double z = height - rho * t - (radius + gap) * lift;
    if (z >= radius) spheres.push_back({{rho * std::cos(phi), rho * std::sin(phi), z}, radius});
  }
  const double pitch = 2.0 * r;
  const int n = static_cast<int>(std::ceil(base / pitch));
  for (int kz = 0; kz * pitch < height; ++kz)
    for (int ix = -n; ix <= n; ++ix)
      for (int iy = -n; iy <= n; ++iy) {
        const double x = ix * pitch, y = iy * pitch, z = r + kz * pitch;
        if (z + 2.0 * r * lift <= height - std::hypot(x, y) * t) spheres.push_back({{x, y, z}, r});
      }
  return spheres;
}

// A ridge along y (length 2 * half_length) with a left face rising at left_deg and a right face
// falling at right_deg, crest `height` above the floor at x = 0; sphere centres on both faces.
inline std::vector<Sphere> wedge_shell(double height, double left_deg, double right_deg, double r, double half_length) {
  std::vector<Sphere> spheres;
  const double tl = std::tan(radians(left_deg)), tr = std::tan(radians(right_deg));
  const int rows = static_cast<int>(std::ceil(half_length / r));
  for (int iy = -rows; iy <= rows; ++iy) {
    const double y = half_length * iy / rows;
    for (double x = -height / tl; x <= 0; x += 0.5 * r) spheres.push_back({{x, y, height + x * tl}, r});
    for (double x = 0.5 * r; x <= height / tr; x += 0.5 * r) spheres.push_back({{x, y, height - x * tr}, r});
  }
  return spheres;
}

}  // namespace repose::test
