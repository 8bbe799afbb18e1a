// Helpers the experiments share: the tested body's centre and extent from the host state, and
// finding a case's wall by name.
#pragma once
#include <string>

#include "case/case_spec.h"
#include "engine/backend.h"

namespace repose {

// Mass-weighted centre of all particles (the body or group under test).
Vec3d body_centre(const HostState& state);
// Index of the [[wall]] named `name`, or of the first wall when `name` is empty; throws
// std::runtime_error naming the case when there is none.
size_t find_wall(const CaseSpec& spec, const std::string& name, const std::string& role);

}  // namespace repose
