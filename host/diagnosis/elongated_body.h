// Extension `shape`: the case's one sphere replaced by an elongated clump of the same volume and
// material, a chain of seven overlapping spheres along one axis: a central sphere of radius r_c
// and three spheres of radius 0.7 r_c on each side, equally spaced, the outermost touching the
// tip at a r_c. `a` is the aspect ratio (length over the central diameter). At a = 1 every side
// sphere lies inside the central one (their tips touch it from inside on the axis), so the union
// is the sphere, but not its contacts: a soft body's deep overlap lets the side spheres touch
// the plate too when the axis lands near-vertical (measured on the cabbage: rebounds scatter by
// 8-16 mm over 8 orientations at a = 1), so the family is not nested in the sphere. The chain grows
// continuously with a, and r_c shrinks so that the union volume, and hence the mass, stays the
// sphere's.
#pragma once
#include "case/case_spec.h"

namespace repose {

constexpr double kElongatedMinAspect = 1.0, kElongatedMaxAspect = 3.0;

// The chain's sub-spheres for a central radius of 1 (template frame, axis x).
ClumpTemplate elongated_template(double aspect_ratio);

// Replaces spec.spheres[0] (the drop body) by a [[template]] + [[clump]] of the same volume and
// material at the same place. Throws std::runtime_error naming the case when it has no sphere or
// the ratio is outside [1, 3].
void make_body_elongated(CaseSpec& spec, double aspect_ratio);

}  // namespace repose
