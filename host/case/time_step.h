// The Rayleigh time step and the step the engine uses (docs/engineering.md, contact law).
#pragma once
#include "case/case_spec.h"

namespace repose {

// pi R sqrt(rho / G) / (0.1631 nu + 0.8766) for one sphere of the given material.
double rayleigh_time(double radius, const Material& material);

struct RayleighLimit {
  double time = 0;   // the smallest Rayleigh time over all spheres and sub-spheres; +inf without
  int sphere = -1;   // the first sphere that has it; -1 when it is a body's sub-sphere (or none)
  int body = -1;     // the first body whose sub-sphere has it
  double radius = 0;
  int material = 0;
  SourceRef where;   // the entry that made that sphere or body
};
RayleighLimit rayleigh_limit(const CaseSpec& spec);

// Minimum over CaseSpec::spheres and the bodies' sub-spheres; +infinity when there are none.
double rayleigh_time(const CaseSpec& spec);

// dt when the case gives it, else rayleigh_fraction x rayleigh_time(spec). Throws CaseError
// when neither or both are set, or when a fraction is given for a case without spheres.
double resolve_dt(const CaseSpec& spec);

}  // namespace repose
