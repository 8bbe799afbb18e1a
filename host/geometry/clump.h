// Multi-sphere rigid bodies (clumps): a template of sub-spheres and its mass properties.
//
// Mass properties come from the union volume of the sub-spheres (overlaps counted once, see
// union_moments.h for the method and its accuracy) times a uniform density, or are given
// explicitly as EDEM allows (mass, centre of mass, inertia tensor), for instance from a CAD model
// of the real object.
#pragma once
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/sphere.h"
#include "geometry/union_moments.h"

namespace repose {

struct ExplicitMassProperties {
  double mass = 0.0;                // kg
  glm::dvec3 centre_of_mass{0.0};   // m, template frame
  glm::dmat3 inertia{0.0};          // kg m^2, about the centre of mass, template axes
};

struct ClumpTemplate {
  std::string name;
  std::vector<Sphere> spheres;  // template frame, metres
  std::optional<ExplicitMassProperties> explicit_properties;
};

struct MassProperties {
  double volume = 0.0;               // union volume of the sub-spheres, m^3
  double mass = 0.0;                 // kg
  glm::dvec3 centre_of_mass{0.0};    // m, template frame
  glm::dmat3 inertia{0.0};           // kg m^2 about the centre of mass, template axes
  glm::dvec3 principal_moments{0.0};  // ascending
  glm::dmat3 principal_axes{1.0};    // column k is the axis of principal_moments[k]; det = +1
  bool is_explicit = false;          // mass, centre and inertia were given, not integrated
};

struct PrincipalAxes {
  glm::dvec3 moments{0.0};  // ascending
  glm::dmat3 axes{1.0};     // columns, right-handed
};

// Eigen-decomposition of a symmetric inertia tensor (Eigen's SelfAdjointEigenSolver) with a
// deterministic frame: moments ascending; each non-degenerate axis has its largest-magnitude
// component positive (the first one on exact ties); the last axis is the cross product of the
// first two. Within a degenerate pair (moments equal to a relative 1e-6 of the largest, as for
// a round stalk) the first axis of the pair is the template axis most perpendicular to the
// unique axis (the first of those within 1e-6), projected; a fully degenerate tensor (a sphere)
// keeps the template axes.
PrincipalAxes principal_axes(const glm::dmat3& inertia);

// Mass properties of the template: the explicit ones if present (density is then unused), else
// the union-volume integrals times density (kg/m^3). The volume is always the union volume.
// Throws std::invalid_argument for a non-positive density, an empty template, a non-positive
// explicit mass or an explicit inertia that is not symmetric positive definite with moments
// obeying the triangle inequality.
MassProperties compute_mass_properties(const ClumpTemplate& clump, double density,
                                       const UnionIntegration& integration = {});

// Inertia tensor about the centre of mass from the central second moment of the volume:
// I = rho (tr(S) 1 - S).
glm::dmat3 inertia_from_second_moment(const glm::dmat3& central_second_moment, double density);

// The template re-expressed in its principal frame: x_template = centre_of_mass + rotation *
// x_principal. Sphere centres are moved accordingly; explicit properties, if present, become
// (mass, origin, diag(moments)).
struct PrincipalFrameTemplate {
  ClumpTemplate clump;
  glm::dvec3 centre_of_mass{0.0};  // in the original template frame
  glm::dmat3 rotation{1.0};        // columns: principal axes in the original frame
};
PrincipalFrameTemplate to_principal_frame(const ClumpTemplate& clump, const MassProperties& properties);

}  // namespace repose
