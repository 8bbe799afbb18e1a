// Principal axes and the re-expression of a template in its principal frame.
#include <catch2/catch.hpp>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "geometry/clump.h"
#include "geometry/templates.h"

using namespace repose;

namespace {

glm::dmat3 rotation(glm::dvec3 axis, double angle) {
  axis /= glm::length(axis);
  const double c = std::cos(angle), s = std::sin(angle);
  glm::dmat3 r;
  for (int col = 0; col < 3; ++col) {
    glm::dvec3 e(0.0);
    e[col] = 1.0;
    r[col] = e * c + glm::cross(axis, e) * s + axis * glm::dot(axis, e) * (1 - c);
  }
  return r;
}

// An asymmetric clump: three unequal spheres off any symmetry.
ClumpTemplate lumpy() {
  return {"lumpy", {{{0, 0, 0}, 0.04}, {{0.05, 0.01, 0}, 0.03}, {{0.01, 0.045, 0.02}, 0.025}}, std::nullopt};
}

}  // namespace

TEST_CASE("principal moments do not depend on the template's orientation", "[principal]") {
  const ClumpTemplate base = lumpy();
  const MassProperties p0 = compute_mass_properties(base, 1000);
  const glm::dmat3 R = rotation({0.3, -0.5, 0.8}, 1.1);
  ClumpTemplate turned = base;
  for (Sphere& s : turned.spheres) s.centre = R * s.centre + glm::dvec3(0.2, 0.1, -0.4);
  const MassProperties p1 = compute_mass_properties(turned, 1000);
  for (int k = 0; k < 3; ++k) CHECK(p1.principal_moments[k] == Approx(p0.principal_moments[k]).epsilon(5e-5));
  // The same body: principal axes turn with it (up to the sign convention).
  for (int k = 0; k < 3; ++k) CHECK(std::abs(glm::dot(p1.principal_axes[k], R * p0.principal_axes[k])) > 1 - 5e-5);
}

TEST_CASE("the principal frame puts the centre of mass at the origin and diagonalises inertia", "[principal]") {
  ClumpTemplate t = lumpy();
  for (Sphere& s : t.spheres) s.centre = rotation({1, 2, 3}, 0.7) * s.centre + glm::dvec3(1, 2, 3);
  const MassProperties p = compute_mass_properties(t, 850);
  CHECK(glm::determinant(p.principal_axes) == Approx(1.0).epsilon(1e-12));
  CHECK(p.principal_moments[0] <= p.principal_moments[1]);
  CHECK(p.principal_moments[1] <= p.principal_moments[2]);

  const PrincipalFrameTemplate frame = to_principal_frame(t, p);
  // Spheres map back exactly: x = com + R x'.
  for (size_t i = 0; i < t.spheres.size(); ++i) {
    glm::dvec3 back = frame.centre_of_mass + frame.rotation * frame.clump.spheres[i].centre;
    CHECK(glm::length(back - t.spheres[i].centre) < 1e-14);
    CHECK(frame.clump.spheres[i].radius == t.spheres[i].radius);
  }
  const MassProperties q = compute_mass_properties(frame.clump, 850);
  CHECK(glm::length(q.centre_of_mass) < 5e-5 * 0.05);
  const double scale = q.principal_moments[2];
  for (int a = 0; a < 3; ++a) {
    CHECK(q.inertia[a][a] == Approx(p.principal_moments[a]).epsilon(5e-5));
    for (int b = 0; b < 3; ++b)
      if (a != b) CHECK(std::abs(q.inertia[a][b]) < 5e-5 * scale);
  }
  // In its own principal frame the axes are the template axes: the convention is a fixed point.
  for (int k = 0; k < 3; ++k) CHECK(q.principal_axes[k][k] > 1 - 5e-5);
}

TEST_CASE("principal axes follow the sign convention and are deterministic", "[principal]") {
  glm::dmat3 inertia(0.0);
  inertia[0][0] = 3;
  inertia[1][1] = 1;
  inertia[2][2] = 2;
  const PrincipalAxes a = principal_axes(inertia);
  CHECK(a.moments == glm::dvec3(1, 2, 3));
  CHECK(a.axes[0] == glm::dvec3(0, 1, 0));
  CHECK(a.axes[1] == glm::dvec3(0, 0, 1));
  CHECK(a.axes[2] == glm::dvec3(1, 0, 0));  // e0 x e1: right-handed
  const PrincipalAxes again = principal_axes(inertia);
  CHECK(again.axes == a.axes);
}

TEST_CASE("a round stalk keeps its transverse axes on the template axes", "[principal]") {
  // Two equal moments: the pair's axes are not left to the eigen-solver's whim.
  const MassProperties p = compute_mass_properties(cotton_stalk(), 120);
  CHECK(p.principal_axes[0].z > 1 - 1e-9);
  CHECK(p.principal_axes[1].x > 1 - 1e-9);
  CHECK(p.principal_axes[2].y > 1 - 1e-9);
}

TEST_CASE("explicit properties are carried into the principal frame", "[principal]") {
  ClumpTemplate t = lumpy();
  ExplicitMassProperties e;
  e.mass = 2.0;
  e.centre_of_mass = {0.01, 0.02, 0.0};
  e.inertia = glm::dmat3(0.0);
  e.inertia[0][0] = 5e-3;
  e.inertia[1][1] = 4e-3;
  e.inertia[2][2] = 3e-3;
  t.explicit_properties = e;
  const MassProperties p = compute_mass_properties(t, 1);
  const PrincipalFrameTemplate frame = to_principal_frame(t, p);
  REQUIRE(frame.clump.explicit_properties);
  CHECK(frame.clump.explicit_properties->mass == 2.0);
  CHECK(frame.clump.explicit_properties->centre_of_mass == glm::dvec3(0.0));
  CHECK(frame.clump.explicit_properties->inertia[0][0] == 3e-3);
  CHECK(frame.clump.explicit_properties->inertia[2][2] == 5e-3);
  const glm::dvec3 expected = glm::transpose(frame.rotation) * (t.spheres[0].centre - e.centre_of_mass);
  CHECK(glm::length(frame.clump.spheres[0].centre - expected) < 1e-15);
}
