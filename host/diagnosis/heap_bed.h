// The bed height of a heap case alone: the repose rig (host/experiments/repose.cpp) filled and
// settled up to the start of the lift, then measured there exactly as run_repose measures it
// (same simulation, batches and sample times, so the same bytes), without the lift and the
// heap's settling: about a third of a heap's cost. The diagnosis uses it when the data measure
// only `bed_height` (the bed's packing, which a size spread changes and friction hardly does).
#pragma once
#include "case/case_spec.h"

namespace repose {

// Twice the volume-weighted mean height of the grains above the case's heap floor (default: the
// lowest sphere bottom) at the first 0.05 s sample at or after the lift wall's motion start.
double measure_bed_height(const CaseSpec& spec);

}  // namespace repose
