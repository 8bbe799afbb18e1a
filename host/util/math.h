// The one home of pi and of the small vector helpers on Vec3d (double, host side). Each formula
// is written out left to right once, so every caller gets the same bits (docs/engineering.md,
// determinism: the host computes what the kernels must not).
#pragma once
#include <array>
#include <cmath>

namespace repose {

inline constexpr double kPi = 3.14159265358979323846;

using Vec3d = std::array<double, 3>;

inline Vec3d add(const Vec3d& a, const Vec3d& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3d mul(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }
// a / |a| as a multiplication by 1 / |a|.
inline Vec3d unit(const Vec3d& a) { return mul(a, 1.0 / std::sqrt(dot(a, a))); }

// Rodrigues rotation of v about the unit axis k by angle a (radians).
inline Vec3d rotate_about(const Vec3d& v, const Vec3d& k, double a) {
  double c = std::cos(a), s = std::sin(a);
  return add(add(mul(v, c), mul(cross(k, v), s)), mul(k, dot(k, v) * (1 - c)));
}

}  // namespace repose
