#include "experiments/experiment_simulation.h"
#include "experiments/repose.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "experiments/body_frame.h"
#include "measure/bed_height.h"
#include "util/progress.h"

namespace repose {

namespace {

// The largest kinetic energy of any free sphere or body: the heap has settled when every
// particle has (the seeds waited until nothing moved).
double max_kinetic_energy(const HostState& st) {
  double most = 0;
  auto sq = [](const gpu::vec4& v) { return double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z; };
  if (!st.bodies.empty()) {
    for (const auto& b : st.bodies) {
      double rot = double(b.omega.x) * b.ang_mom.x + double(b.omega.y) * b.ang_mom.y + double(b.omega.z) * b.ang_mom.z;
      most = std::max(most, 0.5 / b.pos.w * sq(b.vel) + 0.5 * rot);
    }
    return most;
  }
  for (size_t i = 0; i < st.vel.size(); ++i)
    most = std::max(most, 0.5 / st.vel[i].w * sq(st.vel[i]) + 0.5 / st.omega[i].w * sq(st.omega[i]));
  return most;
}

}  // namespace

double bed_height(const HostState& st, const std::optional<double>& floor) {
  std::vector<Sphere> grains;
  grains.reserve(st.pos.size());
  for (const auto& p : st.pos) grains.push_back({{p.x, p.y, p.z}, p.w});
  return uniform_bed_height(grains, floor);
}

ReposeResult run_repose(const CaseSpec& spec, const ExperimentRunOptions& options, bool measure_unsettled) {
  const ExperimentSpec& ex = spec.experiment;
  const WallSpec& lift = spec.walls.at(find_wall(spec, ex.lift_wall, "lifted wall"));
  double lift_end = ex.lift_end > 0 ? ex.lift_end : lift.motion.stop_time;
  if (!(lift_end < 1e29))
    throw std::runtime_error(spec.path + ": [experiment] lift_end is needed: the wall '" + lift.name +
                             "' moves without a stop time");
  if (lift_end >= ex.max_time)
    throw std::runtime_error(spec.path + ": [experiment] max_time must exceed the end of the lift (" +
                             std::to_string(lift_end) + " s)");

  Model model = build_model(spec);
  uint64_t sample_steps = steps_in(0.05, model.dt);
  uint64_t total_steps = uint64_t(ex.max_time / model.dt) + 1;
  Simulation sim = experiment_simulation(model, options, sample_steps, 200);
  Progress progress(spec.name + " repose", total_steps, model.dt, options.progress);

  ReposeResult r;
  bool bed_measured = false;
  while (true) {
    sim.advance(sample_steps);
    if (!bed_measured && sim.time() >= lift.motion.start_time - 1e-9) {
      r.bed_height = bed_height(sim.state(), ex.heap_floor_z);
      bed_measured = true;
    }
    double e = max_kinetic_energy(sim.state());
    r.energy.push_back({sim.time(), e});
    r.wall_forces.sample(sim);
    progress.update(sim.step(), "max E " + std::to_string(e).substr(0, 8) + " J");
    if (sim.time() >= lift_end && e < ex.settle_energy) {
      r.settle_time = sim.time();
      r.kinetic_energy = e;
      break;
    }
    if (sim.time() >= ex.max_time && measure_unsettled) {
      r.settle_time = sim.time();
      r.kinetic_energy = e;
      r.settled = false;
      break;
    }
    if (sim.time() >= ex.max_time)
      throw std::runtime_error(spec.path + ": the heap had not settled (largest kinetic energy " + std::to_string(e) +
                               " J of a particle, settle_energy " + std::to_string(ex.settle_energy) +
                               ") by max_time = " + std::to_string(ex.max_time) + " s");
  }
  progress.finish();

  // The heap: particles whose bottom is not below the heap floor (those that fell off a plate or
  // out of a bucket are not in the picture).
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto& p : sim.state().pos) lowest = std::min(lowest, double(p.z) - p.w);
  double floor_z = ex.heap_floor_z.value_or(lowest);
  for (const auto& p : sim.state().pos)
    if (double(p.z) - p.w >= floor_z - 0.5 * p.w) r.spheres.push_back({{p.x, p.y, p.z}, p.w});
  r.particles_measured = r.spheres.size();
  if (r.spheres.empty()) throw std::runtime_error(spec.path + ": no particle is left above the heap floor");

  HeapAngleOptions opts;
  opts.view = ex.view == "x" ? ViewAxis::X : ViewAxis::Y;
  opts.floor_z = floor_z;
  r.heap = measure_heap_angle(r.spheres, opts);
  r.profile = measure_heap_profile(r.heap);
  if (ex.heap_side == "left") {
    if (!r.heap.left.valid) throw std::runtime_error(spec.path + ": no left slope: " + r.heap.left.problem);
    r.angle_deg = r.heap.left.angle_deg;
  } else if (ex.heap_side == "right") {
    if (!r.heap.right.valid) throw std::runtime_error(spec.path + ": no right slope: " + r.heap.right.problem);
    r.angle_deg = r.heap.right.angle_deg;
  } else {
    if (!r.heap.left.valid && !r.heap.right.valid)
      throw std::runtime_error(spec.path + ": the heap has no measurable slope (" + r.heap.left.problem + ")");
    r.angle_deg = r.heap.mean_deg;
  }
  if (ex.views > 1) {
    r.views = measure_heap_angle_views(r.spheres, ex.views, opts);
    if (r.views->valid_slopes == 0) throw std::runtime_error(spec.path + ": no view of the heap shows a measurable slope");
    r.angle_deg = r.views->mean_deg;
  }
  if (ex.axisymmetric) {
    AxisymmetricOptions a;
    a.floor_z = floor_z;
    r.heap_3d = measure_axisymmetric_heap_angle(r.spheres, a);
  }
  return r;
}

}  // namespace repose
