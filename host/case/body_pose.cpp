#include "case/body_pose.h"

#include <algorithm>
#include <cmath>

namespace repose {

Vec3d rotate(const Quat& q, const Vec3d& v) {
  // v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z)
  Vec3d u{q[1], q[2], q[3]};
  Vec3d t{2 * (u[1] * v[2] - u[2] * v[1]), 2 * (u[2] * v[0] - u[0] * v[2]), 2 * (u[0] * v[1] - u[1] * v[0])};
  return {v[0] + q[0] * t[0] + (u[1] * t[2] - u[2] * t[1]),
          v[1] + q[0] * t[1] + (u[2] * t[0] - u[0] * t[2]),
          v[2] + q[0] * t[2] + (u[0] * t[1] - u[1] * t[0])};
}

Quat multiply(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

Quat quat_from_columns(const Vec3d& c0, const Vec3d& c1, const Vec3d& c2) {
  // m[row][col]; Shepperd's method: divide by the largest of the four candidates.
  double m00 = c0[0], m11 = c1[1], m22 = c2[2];
  double m01 = c1[0], m10 = c0[1], m02 = c2[0], m20 = c0[2], m12 = c2[1], m21 = c1[2];
  double trace = m00 + m11 + m22;
  Quat q;
  if (trace >= m00 && trace >= m11 && trace >= m22) {
    double s = 2 * std::sqrt(1 + trace);
    q = {0.25 * s, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s};
  } else if (m00 >= m11 && m00 >= m22) {
    double s = 2 * std::sqrt(1 + m00 - m11 - m22);
    q = {(m21 - m12) / s, 0.25 * s, (m01 + m10) / s, (m02 + m20) / s};
  } else if (m11 >= m22) {
    double s = 2 * std::sqrt(1 + m11 - m00 - m22);
    q = {(m02 - m20) / s, (m01 + m10) / s, 0.25 * s, (m12 + m21) / s};
  } else {
    double s = 2 * std::sqrt(1 + m22 - m00 - m11);
    q = {(m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, 0.25 * s};
  }
  double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (q[0] < 0) n = -n;  // one sign for the same rotation
  return {q[0] / n, q[1] / n, q[2] / n, q[3] / n};
}

double bounding_radius(const ClumpTemplate& clump) {
  double reach = 0;
  for (const Sphere& s : clump.spheres)
    reach = std::max(reach, std::sqrt(s.centre.x * s.centre.x + s.centre.y * s.centre.y +
                                      s.centre.z * s.centre.z) + s.radius);
  return reach;
}

std::vector<SphereSpec> body_spheres(const BodySpec& body, const TemplateSpec& templ) {
  std::vector<SphereSpec> out;
  out.reserve(templ.clump.spheres.size());
  for (const Sphere& s : templ.clump.spheres) {
    Vec3d local{s.centre.x * body.scale, s.centre.y * body.scale, s.centre.z * body.scale};
    Vec3d r = rotate(body.orientation, local);
    SphereSpec sphere;
    sphere.position = {body.position[0] + r[0], body.position[1] + r[1], body.position[2] + r[2]};
    sphere.radius = s.radius * body.scale;
    sphere.material = body.material;
    sphere.where = body.where;
    out.push_back(sphere);
  }
  return out;
}

}  // namespace repose
