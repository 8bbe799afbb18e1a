#include "diagnosis/heap_bed.h"

#include "engine/model.h"
#include "experiments/body_frame.h"
#include "experiments/experiment_simulation.h"
#include "experiments/repose.h"

namespace repose {

double measure_bed_height(const CaseSpec& spec) {
  const ExperimentSpec& ex = spec.experiment;
  const WallSpec& lift = spec.walls.at(find_wall(spec, ex.lift_wall, "lifted wall"));
  Model model = build_model(spec);
  // run_repose's sampling: batches of 0.05 s, the bed taken at the first sample at the lift.
  uint64_t sample_steps = steps_in(0.05, model.dt);
  Simulation sim = experiment_simulation(model, {}, sample_steps, 200);
  do sim.advance(sample_steps);
  while (sim.time() < lift.motion.start_time - 1e-9);
  return bed_height(sim.state(), ex.heap_floor_z);
}

}  // namespace repose
