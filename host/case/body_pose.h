// Poses of rigid bodies on the host, in double: unit quaternions (w, x, y, z), a template's
// bounding sphere, and the world spheres of a placed body (for overlap checks while placing).
#pragma once
#include <array>
#include <vector>

#include "case/case_spec.h"

namespace repose {

using Quat = std::array<double, 4>;  // (w, x, y, z)

Vec3d rotate(const Quat& q, const Vec3d& v);
Quat multiply(const Quat& a, const Quat& b);
// The rotation whose matrix has these columns (a proper rotation: orthonormal, det +1).
Quat quat_from_columns(const Vec3d& c0, const Vec3d& c1, const Vec3d& c2);
// A rotation drawn uniformly from `uniform()` draws in [0, 1): a point uniform in the 4-ball by
// rejection, normalised (uniform on the 3-sphere; sqrt only, so every libm gives the same bits).
template <class Uniform>
Quat random_orientation(Uniform&& uniform) {
  for (;;) {
    Quat q{2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1};
    double n = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (n > 1e-6 && n <= 1) {
      double inv = 1 / std::sqrt(n);
      return {q[0] * inv, q[1] * inv, q[2] * inv, q[3] * inv};
    }
  }
}

// Radius of the smallest sphere about the template origin that holds every sub-sphere.
double bounding_radius(const ClumpTemplate& clump);

// The body's sub-spheres in the world: position + R (scale c), radius scale r.
std::vector<SphereSpec> body_spheres(const BodySpec& body, const TemplateSpec& templ);

}  // namespace repose
