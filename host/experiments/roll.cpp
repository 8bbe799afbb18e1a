#include "experiments/experiment_simulation.h"
#include "experiments/roll.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "experiments/body_frame.h"
#include "util/progress.h"

namespace repose {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

RollResult run_roll(const CaseSpec& input, const ExperimentRunOptions& options, bool require_stop) {
  CaseSpec spec = input;
  const ExperimentSpec& ex = spec.experiment;
  int plate_material = spec.walls.at(find_wall(spec, ex.plate, "plate (its material)")).material;
  double beta = ex.incline_deg * kPi / 180, S = ex.slope_distance;
  double cb = std::cos(beta), sb = std::sin(beta);
  Vec3d down = {cb, 0, -sb};    // along the incline, downhill
  Vec3d normal = {sb, 0, cb};   // the incline's normal

  // Body: lowest point (along the incline normal) on the incline, centre S uphill of the foot.
  auto spheres = case_spheres(spec);
  if (spheres.empty()) throw std::runtime_error(spec.path + ": a rolling test needs a body");
  Vec3d centre{0, 0, 0};
  double extent = 0;
  for (const auto& s : spheres)
    for (int k = 0; k < 3; ++k) centre[k] += s.position[k] / double(spheres.size());
  double lowest = 1e300;
  for (const auto& s : spheres) {
    double h = 0, d2 = 0;
    for (int k = 0; k < 3; ++k) {
      h += (s.position[k] - centre[k]) * normal[k];
      d2 += (s.position[k] - centre[k]) * (s.position[k] - centre[k]);
    }
    lowest = std::min(lowest, h - s.radius);
    extent = std::max(extent, std::sqrt(d2) + s.radius);
  }
  Vec3d shift;
  for (int k = 0; k < 3; ++k) shift[k] = -centre[k] - S * down[k] - lowest * normal[k];
  shift_to_rest(spec, shift);

  // Rig: the incline (a rectangle from the foot up to beyond the release point) and the floor.
  double length = S + 4 * extent, width = std::max(1.0, 20 * extent);
  WallSpec incline;
  incline.type = WallSpec::Type::Rectangle;
  incline.name = "incline";
  incline.material = plate_material;
  incline.point = {-0.5 * length * down[0], 0, -0.5 * length * down[2]};
  incline.normal = normal;
  incline.edge_axis = down;
  incline.size = {length, width};
  WallSpec floor;
  floor.type = WallSpec::Type::Plane;
  floor.name = "floor";
  floor.material = plate_material;
  floor.point = {0, 0, 0};
  floor.normal = {0, 0, 1};
  spec.walls = {incline, floor};

  Model model = build_model(spec);
  uint64_t sample_steps = steps_in(0.005, model.dt);
  uint64_t total_steps = uint64_t(ex.max_time / model.dt) + 1;
  Simulation sim = experiment_simulation(model, options, sample_steps, 500);
  Progress progress(spec.name + " roll", total_steps, model.dt, options.progress);

  RollResult r;
  r.incline_deg = ex.incline_deg;
  r.slope_distance = S;
  // The centre is above the contact point on the floor; on the incline it is R sin(beta) ahead.
  bool on_floor = false;
  double previous_x = -1e300;
  while (true) {
    if (sim.time() >= ex.max_time && !require_stop) {
      r.rolling_distance = std::max(0.0, previous_x);
      r.stop_time = sim.time();
      r.stopped = false;
      break;
    }
    if (sim.time() >= ex.max_time)
      throw std::runtime_error(spec.path + ": the body had not stopped on the floor after max_time = " +
                               std::to_string(ex.max_time) + " s");
    sim.advance(sample_steps);
    double x = body_centre(sim.state())[0], speed = body_speed(sim.state());
    r.trajectory.push_back({sim.time(), x, speed});
    r.wall_forces.sample(sim);
    progress.update(sim.step(), "x " + std::to_string(x).substr(0, 6) + " m");
    if (!on_floor && x > 0) {
      on_floor = true;
      r.speed_at_foot = speed;
    }
    // Stopped: slow enough, or no longer moving forward (the constant rolling torque rocks a
    // stopped body back and forth by a hair).
    if (on_floor && (speed < ex.stop_speed || x <= previous_x)) {
      r.rolling_distance = std::max(x, previous_x);
      r.stop_time = sim.time();
      break;
    }
    previous_x = x;
  }
  progress.finish();
  r.mu_r = S * std::sin(beta) / (S * std::cos(beta) + r.rolling_distance);
  return r;
}

}  // namespace repose
