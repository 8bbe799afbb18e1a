#include "diagnosis/heap_bed.h"

#include <algorithm>
#include <limits>

#include "engine/model.h"
#include "experiments/body_frame.h"
#include "experiments/experiment_simulation.h"

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
  const HostState& st = sim.state();
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto& p : st.pos) lowest = std::min(lowest, double(p.z) - p.w);
  double floor_z = ex.heap_floor_z.value_or(lowest), volume = 0, moment = 0;
  for (const auto& p : st.pos) {
    double v = double(p.w) * p.w * p.w;
    volume += v;
    moment += v * (double(p.z) - floor_z);
  }
  return volume > 0 ? 2 * moment / volume : 0.0;
}

}  // namespace repose
