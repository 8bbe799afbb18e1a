// The height of a bed of spheres: twice their volume-weighted mean height above the floor, the
// height a uniform bed of the same spheres would have (a uniform bed of height h has its volume's
// centre at h / 2). At a given count it falls as the bed packs denser. Measured on the grains of a
// repose rig before the lift (host/experiments/repose.h), or on a user's own sphere CSV of a bed
// (`repose heap-angle`).
#pragma once
#include <optional>
#include <vector>

#include "geometry/sphere.h"

namespace repose {

// floor_z: default the lowest sphere bottom. 0 for no spheres.
double uniform_bed_height(const std::vector<Sphere>& spheres, const std::optional<double>& floor_z = {});

}  // namespace repose
