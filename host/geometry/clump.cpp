#include "geometry/clump.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

namespace repose {
namespace {

// Flips v so that its largest-magnitude component is positive (the first one on exact ties).
glm::dvec3 canonical_sign(glm::dvec3 v) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(v[i]) > std::abs(v[k])) k = i;
  return v[k] < 0 ? -v : v;
}

// The template axis most perpendicular to the unit vector w, made exactly perpendicular. Axes
// within 1e-6 of the most perpendicular count as tied and the first wins, so integration noise
// in w (a round stalk's axis is z to ~1e-9) cannot pick between x and y.
glm::dvec3 perpendicular_template_axis(const glm::dvec3& w) {
  const double least = std::min({std::abs(w[0]), std::abs(w[1]), std::abs(w[2])});
  int k = 0;
  while (std::abs(w[k]) > least + 1e-6) ++k;
  glm::dvec3 e(0.0);
  e[k] = 1.0;
  glm::dvec3 a = e - glm::dot(e, w) * w;
  return a / glm::length(a);
}

void check_symmetric_tensor(const glm::dmat3& m, const char* what) {
  double scale = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (!std::isfinite(m[a][b])) throw std::invalid_argument(std::string(what) + " has a non-finite entry");
      scale = std::max(scale, std::abs(m[a][b]));
    }
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (std::abs(m[a][b] - m[b][a]) > 1e-9 * scale)
        throw std::invalid_argument(std::string(what) + " is not symmetric");
}

}  // namespace

PrincipalAxes principal_axes(const glm::dmat3& inertia) {
  Eigen::Matrix3d m;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) m(a, b) = 0.5 * (inertia[a][b] + inertia[b][a]);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m);  // eigenvalues come ascending
  if (solver.info() != Eigen::Success) throw std::runtime_error("principal_axes: eigen-solver failed");

  PrincipalAxes out;
  glm::dvec3 v[3];
  for (int k = 0; k < 3; ++k) {
    out.moments[k] = solver.eigenvalues()(k);
    v[k] = glm::dvec3(solver.eigenvectors()(0, k), solver.eigenvectors()(1, k), solver.eigenvectors()(2, k));
    v[k] /= glm::length(v[k]);
  }
  const double tolerance = 1e-6 * std::max(std::abs(out.moments[2]), std::abs(out.moments[0]));
  const bool low_pair = out.moments[1] - out.moments[0] <= tolerance;
  const bool high_pair = out.moments[2] - out.moments[1] <= tolerance;

  glm::dvec3 axes[3];
  if (low_pair && high_pair) {
    axes[0] = {1, 0, 0};
    axes[1] = {0, 1, 0};
    axes[2] = {0, 0, 1};
  } else if (low_pair) {  // unique axis is the last one
    axes[2] = canonical_sign(v[2]);
    axes[0] = perpendicular_template_axis(axes[2]);
    axes[1] = glm::cross(axes[2], axes[0]);
  } else if (high_pair) {  // unique axis is the first one
    axes[0] = canonical_sign(v[0]);
    axes[1] = perpendicular_template_axis(axes[0]);
    axes[2] = glm::cross(axes[0], axes[1]);
  } else {
    axes[0] = canonical_sign(v[0]);
    axes[1] = canonical_sign(v[1]);
    axes[2] = glm::cross(axes[0], axes[1]);
  }
  for (int k = 0; k < 3; ++k) out.axes[k] = axes[k];
  return out;
}

glm::dmat3 inertia_from_second_moment(const glm::dmat3& s, double density) {
  const double trace = s[0][0] + s[1][1] + s[2][2];
  glm::dmat3 inertia(0.0);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) inertia[a][b] = density * ((a == b ? trace : 0.0) - s[a][b]);
  return inertia;
}

MassProperties compute_mass_properties(const ClumpTemplate& clump, double density,
                                       const UnionIntegration& integration) {
  if (clump.spheres.empty())
    throw std::invalid_argument("clump '" + clump.name + "' has no sub-spheres");
  MassProperties out;
  const UnionMoments moments = union_moments(clump.spheres, integration);
  out.volume = moments.volume;

  if (clump.explicit_properties) {
    const ExplicitMassProperties& e = *clump.explicit_properties;
    if (!(e.mass > 0) || !std::isfinite(e.mass))
      throw std::invalid_argument("clump '" + clump.name + "': explicit mass must be positive");
    check_symmetric_tensor(e.inertia, "explicit inertia tensor");
    out.mass = e.mass;
    out.centre_of_mass = e.centre_of_mass;
    out.inertia = e.inertia;
    out.is_explicit = true;
  } else {
    if (!(density > 0) || !std::isfinite(density))
      throw std::invalid_argument("density must be positive (kg/m^3)");
    out.mass = density * moments.volume;
    out.centre_of_mass = moments.centroid;
    out.inertia = inertia_from_second_moment(moments.central_second_moment, density);
  }

  const PrincipalAxes principal = principal_axes(out.inertia);
  out.principal_moments = principal.moments;
  out.principal_axes = principal.axes;
  if (out.is_explicit) {
    const glm::dvec3& m = out.principal_moments;
    if (!(m[0] > 0) || m[0] + m[1] < m[2] * (1 - 1e-9))
      throw std::invalid_argument(
          "clump '" + clump.name +
          "': explicit inertia is not physical (principal moments must be positive and each at "
          "most the sum of the other two)");
  }
  return out;
}

PrincipalFrameTemplate to_principal_frame(const ClumpTemplate& clump, const MassProperties& properties) {
  PrincipalFrameTemplate out;
  out.centre_of_mass = properties.centre_of_mass;
  out.rotation = properties.principal_axes;
  out.clump.name = clump.name;
  const glm::dmat3 to_body = glm::transpose(properties.principal_axes);
  out.clump.spheres.reserve(clump.spheres.size());
  for (const Sphere& s : clump.spheres)
    out.clump.spheres.push_back({to_body * (s.centre - properties.centre_of_mass), s.radius});
  if (clump.explicit_properties) {
    ExplicitMassProperties e;
    e.mass = properties.mass;
    e.centre_of_mass = glm::dvec3(0.0);
    e.inertia = glm::dmat3(0.0);
    for (int k = 0; k < 3; ++k) e.inertia[k][k] = properties.principal_moments[k];
    out.clump.explicit_properties = e;
  }
  return out;
}

}  // namespace repose
