// The cabbage study's restitution test between cabbages (Zheng et al., section 2.3.1): several
// cabbages bonded together and fixed on the bottom plate, one cabbage released 500 mm above them,
// its highest rebound h read by a high-speed camera; e = sqrt(h/H) (measured h 71.45-116.32 mm, e
// 0.38-0.48). In a case it is a drop ([experiment] type = "drop") that holds fixed particles, the
// bed (`fixed = true` on [[sphere]], [[clump]], [[fill]] or [[lattice]]): the body is the one
// sphere or clump that moves, released with its lowest point drop_height above the bed's highest
// point, and the camera measures from there. Registered as its own experiment (registry.cpp), a
// variant of the drop: the same keys, outcome, files and diagnosis, with the bed for the plate.
#pragma once
#include "experiments/drop.h"

namespace repose {

const Experiment& drop_on_bed_experiment();

}  // namespace repose
