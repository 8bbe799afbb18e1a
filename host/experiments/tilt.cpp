#include "experiments/tilt.h"

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

Vec3d sub(Vec3d a, Vec3d b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(Vec3d a, Vec3d b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d cross(Vec3d a, Vec3d b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Rodrigues rotation of v about the unit axis k by angle a.
Vec3d rotate(Vec3d v, Vec3d k, double a) {
  double c = std::cos(a), s = std::sin(a);
  Vec3d kv = cross(k, v);
  double kd = dot(k, v) * (1 - c);
  return {v[0] * c + kv[0] * s + k[0] * kd, v[1] * c + kv[1] * s + k[1] * kd, v[2] * c + kv[2] * s + k[2] * kd};
}

}  // namespace

TiltResult run_tilt(const CaseSpec& input, const ExperimentRunOptions& options) {
  CaseSpec spec = input;
  const ExperimentSpec& ex = spec.experiment;
  size_t plate_index = find_wall(spec, ex.plate, "tilting plate");
  WallSpec& plate = spec.walls[plate_index];
  if (plate.type != WallSpec::Type::Rectangle && plate.type != WallSpec::Type::Plane)
    throw std::runtime_error(spec.path + ": the tilting plate '" + plate.name + "' must be a rectangle or a plane");
  double rate = ex.tilt_rate_deg * kPi / 180.0;
  Vec3d pivot = plate.point;
  plate.motion = WallMotion{};
  plate.motion.rotation_axis_point = pivot;
  plate.motion.rotation_axis = ex.tilt_axis;
  plate.motion.angular_rate = rate;
  plate.motion.start_time = ex.settle_time;
  plate.motion.stop_time = ex.settle_time + ex.max_angle_deg * kPi / 180.0 / rate;

  Model model = build_model(spec);
  double sample_dt = std::min(0.01, 0.05 * kPi / 180.0 / rate);  // every 0.05 degrees at most
  auto sample_steps = std::max<uint64_t>(1, uint64_t(std::llround(sample_dt / model.dt)));
  double end_time = std::min(ex.max_time, plate.motion.stop_time);
  uint64_t total_steps = uint64_t(end_time / model.dt) + 1;
  Simulation sim(model, make_backend(options.backend, options.device, options.threads, gpu::kDefaultWorkgroup),
                 {}, uint32_t(std::min<uint64_t>(sample_steps, 500)));
  Progress progress(spec.name + " tilt", total_steps, model.dt, options.progress);

  TiltResult r;
  auto settle_steps = uint64_t(std::llround(ex.settle_time / model.dt));
  sim.advance(settle_steps);
  // The body in the plate's frame: rotate back by the tilt so far (exact on the host, in double).
  auto in_plate_frame = [&](Vec3d x, double t) {
    double angle = rate * std::max(0.0, t - ex.settle_time);
    return rotate(sub(x, pivot), ex.tilt_axis, -angle);
  };
  Vec3d start = in_plate_frame(body_centre(sim.state()), sim.time());
  Vec3d start_first = in_plate_frame({sim.state().pos[0].x, sim.state().pos[0].y, sim.state().pos[0].z}, sim.time());
  double spin_angle = 0;  // first particle's rotation angle since the tilt began (|w| dt summed)
  TiltSample previous{sim.time(), 0, 0};
  r.trajectory.push_back(previous);
  r.wall_forces.sample(sim);
  while (true) {
    if (sim.time() >= end_time)
      throw std::runtime_error(spec.path + ": the body did not move by " + std::to_string(ex.onset_distance) +
                               " m up to a tilt of " + std::to_string(rate * (sim.time() - ex.settle_time) * 180 / kPi) +
                               " degrees (max_angle, max_time)");
    sim.advance(sample_steps);
    const auto& w = sim.state().omega[0];
    spin_angle += std::sqrt(double(w.x) * w.x + double(w.y) * w.y + double(w.z) * w.z) * sample_steps * model.dt;
    Vec3d moved = sub(in_plate_frame(body_centre(sim.state()), sim.time()), start);
    TiltSample s{sim.time(), rate * (sim.time() - ex.settle_time) * 180 / kPi, std::sqrt(dot(moved, moved))};
    r.trajectory.push_back(s);
    r.wall_forces.sample(sim);
    progress.update(sim.step(), "tilt " + std::to_string(s.angle_deg).substr(0, 5) + " deg");
    if (s.displacement >= ex.onset_distance) {
      // The angle where the displacement crossed the threshold, between the two samples.
      double f = (ex.onset_distance - previous.displacement) / (s.displacement - previous.displacement);
      r.onset_angle_deg = previous.angle_deg + f * (s.angle_deg - previous.angle_deg);
      r.onset_time = previous.time + f * (s.time - previous.time);
      Vec3d first = sub(in_plate_frame({sim.state().pos[0].x, sim.state().pos[0].y, sim.state().pos[0].z}, sim.time()),
                        start_first);
      double first_moved = std::sqrt(dot(first, first));
      r.rolled_fraction = first_moved > 0 ? spin_angle * sim.state().pos[0].w / first_moved : 0;
      break;
    }
    previous = s;
  }
  progress.finish();
  r.tan_alpha = std::tan(r.onset_angle_deg * kPi / 180);
  return r;
}

}  // namespace repose
