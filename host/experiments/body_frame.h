// Helpers the experiments share: the tested body's (or group's) centre, speed and spin from the
// host state, with free spheres or rigid bodies alike; its spheres as placed in a case; and
// finding a case's wall by name.
#pragma once
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "engine/backend.h"

namespace repose {

// Mass-weighted centre of all particles or bodies.
Vec3d body_centre(const HostState& state);
// Speed of the centre of mass of everything.
double body_speed(const HostState& state);
// Angular velocity of the first body (or free sphere), rad/s.
Vec3d first_body_spin(const HostState& state);
// Every sphere of the case as placed (free spheres and the bodies' sub-spheres).
std::vector<SphereSpec> case_spheres(const CaseSpec& spec);
// Moves every free sphere and body of the case by `shift` and sets them at rest.
void shift_to_rest(CaseSpec& spec, const Vec3d& shift);
// Index of the [[wall]] named `name`, or of the first wall when `name` is empty; throws
// std::runtime_error naming the case when there is none.
size_t find_wall(const CaseSpec& spec, const std::string& name, const std::string& role);
// The [[interaction]] of materials a and b (either order); throws naming the case and `what`
// ("the body and the plate") when the case gives none.
Interaction& interaction_between(CaseSpec& spec, int a, int b, const std::string& what);

}  // namespace repose
