// Angle-of-repose rigs of the seeds: the particles settle in a container, one wall of it lifts
// or is pulled (drawing-plate baffle, bottomless cylinder, bucket gate: the case's [[wall]]
// motion), the heap settles, and its angle is measured from a front-view picture as the seeds
// did (host/measure): both slopes, their mean, and for axisymmetric heaps a 3D sector fit.
#pragma once
#include <optional>
#include <vector>

#include "case/case_spec.h"
#include "engine/backend.h"
#include "experiments/run_options.h"
#include "experiments/wall_force_series.h"
#include "measure/heap_angle.h"
#include "measure/heap_profile.h"
#include "measure/heap_views.h"

namespace repose {

struct ReposeResult {
  double angle_deg = 0;           // per [experiment] heap_side: left, right or their mean
  HeapAngle heap;                 // the 2D measurement (with its picture)
  HeapProfile profile;            // the same picture's height, run-out and convexity per side
  std::optional<HeapViewsAngle> views;  // [experiment] views > 1: then angle_deg is their mean
  std::optional<AxisymmetricHeapAngle> heap_3d;
  double settle_time = 0;         // s when the heap was judged settled
  // The bed before the lift (first sample at or after the lift wall's motion start): twice the
  // volume-weighted mean height of the particles above the floor, the height a uniform bed of
  // the same particles would have. At a given count it falls as the bed packs denser.
  double bed_height = 0;          // m
  double kinetic_energy = 0;      // J, the largest of any particle (or body) then
  bool settled = true;            // false: measured at max_time while something still moved
                                  // (only when the caller allows it, see run_repose)
  size_t particles_measured = 0;  // above the heap floor
  std::vector<std::pair<double, double>> energy;  // (t, largest kinetic energy of a particle)
  std::vector<Sphere> spheres;    // the settled heap
  WallForceSeries wall_forces;
};

// Runs until the lift is over (lift_end, default the lift wall's motion stop) and the kinetic
// energy of every particle (or body) is below settle_energy, then measures. Throws std::runtime_error naming
// the case when the heap has not settled by max_time (unless `measure_unsettled`: then it measures
// the heap as it stands at max_time, settled = false; the diagnosis does, since a lone grain that
// keeps spinning on the floor, as one can under rolling = "epsd", which has no twisting
// resistance, leaves the heap's shape as it is) or the measurement finds no slope.
// The bed height (measure/bed_height.h) of the grains in a simulation state.
double bed_height(const HostState& state, const std::optional<double>& floor_z);

ReposeResult run_repose(const CaseSpec& spec, const ExperimentRunOptions& options = {},
                        bool measure_unsettled = false);

}  // namespace repose
