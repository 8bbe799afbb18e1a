// The simulation every virtual experiment drives: the case's model on the chosen backend, in
// batches that end on each sample the experiment takes (so samples land on exact steps).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "engine/backend_factory.h"
#include "engine/simulation.h"
#include "experiments/run_options.h"

namespace repose {

// Steps in `seconds` of simulated time at time step dt, at least one.
inline uint64_t steps_in(double seconds, double dt) {
  return std::max<uint64_t>(1, uint64_t(std::llround(seconds / dt)));
}

// The simulation, writing frames as it goes when the options ask for them.
inline Simulation experiment_simulation(const Model& model, const ExperimentRunOptions& options,
                                        uint64_t sample_steps, uint64_t max_batch) {
  Simulation sim(model, make_backend(options.backend, options.device, options.threads, gpu::kDefaultWorkgroup),
                 KernelVariant::fastest_for(options.backend, model), uint32_t(std::min(sample_steps, max_batch)));
  if (options.wall_impulses) sim.sum_wall_forces();
  record_frames(sim, options.frames);
  return sim;
}

}  // namespace repose
