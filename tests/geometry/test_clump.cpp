// Clump mass properties against closed forms. Collinear spheres have exact slab formulas: the
// union of spheres is the union of each sphere cut by its power-diagram cell, and for centres
// on one line those cells are slabs between radical planes, so every moment is a polynomial
// integral over disks.
#include <catch2/catch.hpp>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "geometry/clump.h"
#include "geometry/templates.h"
#include "util/math.h"

using namespace repose;

namespace {

constexpr double kTolerance = 3e-5;  // measured worst at the defaults: 1.7e-5 (see union_moments.h)

struct AxialMoments {
  double volume = 0, first = 0, second_axial = 0;  // integrals of 1, s, s^2 along the axis
  double second_radial = 0;                          // integral of x^2 (= of y^2)
};

// Spheres with centres at z[k] on the z axis, sorted, each cell bounded by radical planes.
AxialMoments collinear_union(const std::vector<double>& z, const std::vector<double>& r) {
  AxialMoments m;
  for (size_t k = 0; k < z.size(); ++k) {
    double lo = -r[k], hi = r[k];  // local coordinate s = z - z[k]
    if (k > 0) {
      double d = z[k] - z[k - 1];
      double plane = (d * d + r[k - 1] * r[k - 1] - r[k] * r[k]) / (2 * d);  // from z[k-1]
      lo = std::max(lo, z[k - 1] + plane - z[k]);
    }
    if (k + 1 < z.size()) {
      double d = z[k + 1] - z[k];
      double plane = (d * d + r[k] * r[k] - r[k + 1] * r[k + 1]) / (2 * d);
      hi = std::min(hi, plane);
    }
    if (hi <= lo) continue;
    const double R2 = r[k] * r[k];
    auto F0 = [&](double s) { return R2 * s - s * s * s / 3; };                        // (R2 - s^2)
    auto F1 = [&](double s) { return R2 * s * s / 2 - s * s * s * s / 4; };            // (R2 - s^2) s
    auto F2 = [&](double s) { return R2 * s * s * s / 3 - s * s * s * s * s / 5; };    // (R2 - s^2) s^2
    auto F4 = [&](double s) { return R2 * R2 * s - 2 * R2 * s * s * s / 3 + s * s * s * s * s / 5; };
    const double f0 = F0(hi) - F0(lo), f1 = F1(hi) - F1(lo), f2 = F2(hi) - F2(lo), f4 = F4(hi) - F4(lo);
    m.volume += kPi * f0;
    m.first += kPi * (z[k] * f0 + f1);
    m.second_axial += kPi * (z[k] * z[k] * f0 + 2 * z[k] * f1 + f2);
    m.second_radial += kPi / 4 * f4;
  }
  return m;
}

// Volume, centroid along the axis and inertia (unit density) about the centroid: axial, transverse.
struct AxialBody {
  double volume, centroid, axial_inertia, transverse_inertia;
};
AxialBody axial_body(const std::vector<double>& z, const std::vector<double>& r) {
  AxialMoments m = collinear_union(z, r);
  double c = m.first / m.volume;
  double central_axial = m.second_axial - m.volume * c * c;
  return {m.volume, c, 2 * m.second_radial, m.second_radial + central_axial};
}

// Places collinear spheres along a unit direction from an origin; returns the template.
ClumpTemplate along(const glm::dvec3& origin, glm::dvec3 direction, const std::vector<double>& z,
                    const std::vector<double>& r) {
  direction /= glm::length(direction);
  ClumpTemplate t;
  t.name = "collinear";
  for (size_t k = 0; k < z.size(); ++k) t.spheres.push_back({origin + z[k] * direction, r[k]});
  return t;
}

// Expected inertia tensor of an axisymmetric body with the given axis.
glm::dmat3 axisymmetric_tensor(glm::dvec3 axis, double axial, double transverse) {
  axis /= glm::length(axis);
  glm::dmat3 m(0.0);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) m[a][b] = (a == b ? transverse : 0.0) + (axial - transverse) * axis[a] * axis[b];
  return m;
}

double max_relative_tensor_error(const glm::dmat3& got, const glm::dmat3& want) {
  double scale = 0, worst = 0;
  for (int a = 0; a < 3; ++a) scale = std::max(scale, std::abs(want[a][a]));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) worst = std::max(worst, std::abs(got[a][b] - want[a][b]) / scale);
  return worst;
}

void check_collinear(const ClumpTemplate& t, const AxialBody& want, const glm::dvec3& origin,
                     glm::dvec3 direction, double tolerance, const UnionIntegration& options = {}) {
  direction /= glm::length(direction);
  const MassProperties p = compute_mass_properties(t, 1.0, options);
  CHECK(std::abs(p.volume / want.volume - 1) < tolerance);
  CHECK(std::abs(p.mass / want.volume - 1) < tolerance);
  const glm::dvec3 centroid = origin + want.centroid * direction;
  CHECK(glm::length(p.centre_of_mass - centroid) < tolerance * std::cbrt(want.volume));
  const glm::dmat3 expected = axisymmetric_tensor(direction, want.axial_inertia, want.transverse_inertia);
  CHECK(max_relative_tensor_error(p.inertia, expected) < tolerance);
}

}  // namespace

// Tolerance: 3e-5 relative on volume, mass, centroid (relative to V^(1/3)) and every inertia
// entry (relative to the largest moment), at the default integration settings (union_moments.h).
TEST_CASE("one sphere: volume, centre and inertia 2/5 m r^2", "[clump]") {
  const double r = 0.37;
  ClumpTemplate t{"ball", {{{0.3, -1.2, 2.5}, r}}, std::nullopt};
  const MassProperties p = compute_mass_properties(t, 850.0);
  const double volume = 4.0 / 3.0 * kPi * r * r * r;
  CHECK(std::abs(p.volume / volume - 1) < kTolerance);
  CHECK(std::abs(p.mass / (850.0 * volume) - 1) < kTolerance);
  CHECK(glm::length(p.centre_of_mass - glm::dvec3(0.3, -1.2, 2.5)) < kTolerance * r);
  const double moment = 0.4 * p.mass * r * r;
  CHECK(max_relative_tensor_error(p.inertia, glm::dmat3(moment)) < kTolerance);
  // A sphere's tensor is fully degenerate: the template axes are kept.
  CHECK(p.principal_axes == glm::dmat3(1.0));
}

TEST_CASE("two overlapping equal spheres: lens-subtracted volume and inertia", "[clump]") {
  const double r = 0.05, d = 0.06;  // overlap depth 2r - d = 40 mm
  const AxialBody want = axial_body({0, d}, {r, r});
  // The closed-form lens: V = 2 (4/3 pi r^3) - pi (4r + d)(2r - d)^2 / 12.
  const double lens = kPi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12;
  REQUIRE(std::abs(want.volume - (2 * 4.0 / 3.0 * kPi * r * r * r - lens)) < 1e-15);
  const glm::dvec3 origin(0.01, 0.02, -0.03);
  for (glm::dvec3 direction : {glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), glm::dvec3(1, 2, 2)}) {
    INFO("direction " << direction.x << " " << direction.y << " " << direction.z);
    check_collinear(along(origin, direction, {0, d}, {r, r}), want, origin, direction, kTolerance);
  }
  SECTION("lines across the lens (kinks in the chord union) agree as well") {
    for (int axis = 0; axis < 3; ++axis) {
      UnionIntegration options;
      options.line_axis = axis;
      check_collinear(along(origin, {1, 2, 2}, {0, d}, {r, r}), want, origin, {1, 2, 2}, kTolerance, options);
    }
  }
}

TEST_CASE("two overlapping unequal spheres: inclusion-exclusion volume", "[clump]") {
  const double r1 = 0.08, r2 = 0.03, d = 0.09;
  const AxialBody want = axial_body({0, d}, {r1, r2});
  const double lens = kPi * (r1 + r2 - d) * (r1 + r2 - d) *
                      (d * d + 2 * d * r2 - 3 * r2 * r2 + 2 * d * r1 + 6 * r1 * r2 - 3 * r1 * r1) / (12 * d);
  REQUIRE(std::abs(want.volume / (4.0 / 3.0 * kPi * (r1 * r1 * r1 + r2 * r2 * r2) - lens) - 1) < 1e-13);
  check_collinear(along({0, 0, 0}, {2, -1, 3}, {0, d}, {r1, r2}), want, {0, 0, 0}, {2, -1, 3}, kTolerance);
}

TEST_CASE("chain of spheres, with triple overlaps", "[clump]") {
  const double r = 0.01;
  for (double pitch : {1.5 * r, 0.7 * r}) {  // 0.7 r: every sphere overlaps its second neighbour
    INFO("pitch " << pitch);
    std::vector<double> z, radii;
    for (int k = 0; k < 7; ++k) {
      z.push_back(k * pitch);
      radii.push_back(r);
    }
    const AxialBody want = axial_body(z, radii);
    check_collinear(along({0.1, 0.2, 0.3}, {3, 1, -2}, z, radii), want, {0.1, 0.2, 0.3}, {3, 1, -2}, kTolerance);
  }
}

// A rod of 141 spheres (radius 5 mm, 0.5 mm pitch) is a capsule with 6 micrometre ripples:
// against the analytic solid capsule (cylinder of 70 mm with hemispherical ends) within 0.5 %.
TEST_CASE("cylinder-like rod against the analytic capsule", "[clump]") {
  const double R = 0.005, pitch = 0.0005;
  ClumpTemplate rod;
  for (int k = -70; k <= 70; ++k) rod.spheres.push_back({{0, 0, k * pitch}, R});
  const MassProperties p = compute_mass_properties(rod, 1.0);
  const double L = 0.070;
  const double cylinder = kPi * R * R * L, ball = 4.0 / 3.0 * kPi * R * R * R;
  const double axial = cylinder * R * R / 2 + ball * 0.4 * R * R;
  // Each hemisphere (mass m_h): 2/5 m_h R^2 about a transverse axis in its flat face, centroid
  // 3R/8 from that face, so 83/320 m_h R^2 about its centroid, then the parallel-axis shift.
  const double hemisphere = ball / 2, offset = L / 2 + 3 * R / 8;
  const double transverse = cylinder * (3 * R * R + L * L) / 12 +
                            2 * (83.0 / 320.0 * hemisphere * R * R + hemisphere * offset * offset);
  CHECK(std::abs(p.volume / (cylinder + ball) - 1) < 5e-3);
  CHECK(std::abs(p.principal_moments[0] / axial - 1) < 5e-3);
  CHECK(std::abs(p.principal_moments[2] / transverse - 1) < 5e-3);
}

// The cotton-stalk study's stalk is a ring of spheres (hollow), so its analytic counterpart is a thick-walled
// tube (inner radius 3 mm, outer 5 mm, 80 mm long). Per unit mass: transverse radius of gyration
// squared within 0.5 % (the length dominates), axial within 5 % (spheres put less mass at the
// outer wall than a tube).
TEST_CASE("cotton stalk against the analytic thick-walled tube", "[clump]") {
  const MassProperties p = compute_mass_properties(cotton_stalk(), 120.0);
  const double inner = 0.003, outer = 0.005, length = 0.080;
  const double axial_k2 = (inner * inner + outer * outer) / 2;
  const double transverse_k2 = (3 * (inner * inner + outer * outer) + length * length) / 12;
  CHECK(std::abs(p.principal_moments[0] / p.mass / axial_k2 - 1) < 0.05);
  CHECK(std::abs(p.principal_moments[1] / p.mass / transverse_k2 - 1) < 0.005);
  CHECK(std::abs(p.principal_moments[2] / p.mass / transverse_k2 - 1) < 0.005);
  // The long axis is the axis of least inertia.
  CHECK(std::abs(p.principal_axes[0].z) > 1 - 1e-12);
  // The union counts overlaps once: less than 720 separate spheres, more than the tube's
  // material inside the spheres' reach would allow if they were disjoint.
  const double separate = 720 * 4.0 / 3.0 * kPi * 1e-9;
  CHECK(p.volume < separate);
  CHECK(p.volume > 0.5 * separate);
}

TEST_CASE("explicit mass properties replace the integrated ones", "[clump]") {
  ClumpTemplate t{"given", {{{0, 0, 0}, 0.05}, {{0.06, 0, 0}, 0.05}}, std::nullopt};
  ExplicitMassProperties e;
  e.mass = 0.958;
  e.centre_of_mass = {0.03, 0.001, 0};
  e.inertia = glm::dmat3(0.0);
  e.inertia[0][0] = 2e-3;
  e.inertia[1][1] = 3e-3;
  e.inertia[2][2] = 4e-3;
  e.inertia[0][1] = e.inertia[1][0] = 1e-4;
  t.explicit_properties = e;
  const MassProperties p = compute_mass_properties(t, 0.0 /* unused when explicit */);
  CHECK(p.is_explicit);
  CHECK(p.mass == e.mass);
  CHECK(p.centre_of_mass == e.centre_of_mass);
  CHECK(p.inertia == e.inertia);
  CHECK(p.volume > 0);
  CHECK(p.principal_moments[0] + p.principal_moments[1] + p.principal_moments[2] == Approx(9e-3).epsilon(1e-12));

  SECTION("non-physical inertia is refused") {
    t.explicit_properties->inertia[2][2] = 6e-3;  // 2 + 3 < 6: violates the triangle inequality
    CHECK_THROWS_WITH(compute_mass_properties(t, 1.0), Catch::Contains("not physical"));
  }
  SECTION("non-symmetric inertia is refused") {
    t.explicit_properties->inertia[0][1] = 2e-4;
    CHECK_THROWS_WITH(compute_mass_properties(t, 1.0), Catch::Contains("not symmetric"));
  }
  SECTION("non-positive mass is refused") {
    t.explicit_properties->mass = 0;
    CHECK_THROWS_WITH(compute_mass_properties(t, 1.0), Catch::Contains("mass must be positive"));
  }
}

TEST_CASE("invalid clumps and densities are refused", "[clump]") {
  ClumpTemplate empty{"empty", {}, std::nullopt};
  CHECK_THROWS_WITH(compute_mass_properties(empty, 1000), Catch::Contains("no sub-spheres"));
  ClumpTemplate ball{"ball", {{{0, 0, 0}, 0.1}}, std::nullopt};
  CHECK_THROWS_WITH(compute_mass_properties(ball, -5), Catch::Contains("density must be positive"));
  ClumpTemplate flat{"flat", {{{0, 0, 0}, 0.0}}, std::nullopt};
  CHECK_THROWS_AS(compute_mass_properties(flat, 1000), std::invalid_argument);
}
