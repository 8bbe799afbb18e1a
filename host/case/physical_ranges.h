// Values a case cannot mean (a unit slip: MPa typed as Pa, millimetres as metres, g/cm^3 as
// kg/m^3) stop the load with a CaseError at the key's line; values that are possible but
// unusual become warnings ("FILE:LINE: KEY: warning: ...") in CaseSpec::warnings, which the
// verbs print before the run.
#pragma once
#include <string>
#include <vector>

#include "case/case_spec.h"

namespace repose {

// Per value, as the loader reads it (`where` names the key and its line).
void check_density(double density, const SourceRef& where, std::vector<std::string>& warnings);
void check_shear_modulus(double shear_modulus, const SourceRef& where, std::vector<std::string>& warnings);

// On the expanded case: particle sizes against the walls that hold them, fills inside their
// walls, the time step against end_time, initial speeds against the time step.
void check_case_ranges(CaseSpec& spec);

}  // namespace repose
