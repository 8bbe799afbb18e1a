#include "experiments/drop.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "case/body_pose.h"
#include "case/particle_factory.h"
#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"

namespace repose {

namespace {

double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Vertex of the parabola through three equally spaced samples (the camera's sub-frame estimate).
double parabola_peak(double a, double b, double c) {
  double denom = a - 2 * b + c;
  if (denom >= 0) return b;
  double offset = 0.5 * (a - c) / denom;
  return b - 0.25 * (a - c) * offset;
}

}  // namespace

DropResult run_drop(const CaseSpec& input, const DropOptions& options) {
  CaseSpec spec = input;
  const ExperimentSpec& ex = spec.experiment;
  bool clump = spec.spheres.empty() && spec.bodies.size() == 1;
  if (!clump && !(spec.spheres.size() == 1 && spec.bodies.empty()))
    throw std::runtime_error(spec.path + ": a drop test needs exactly one body (a [[sphere]] or a [[clump]]); the case has " +
                             std::to_string(spec.spheres.size()) + " spheres and " +
                             std::to_string(spec.bodies.size()) + " clumps");
  auto plate = std::find_if(spec.walls.begin(), spec.walls.end(),
                            [](const WallSpec& w) { return w.type == WallSpec::Type::Plane; });
  if (plate == spec.walls.end())
    throw std::runtime_error(spec.path + ": a drop test needs a plane [[wall]] as the plate");
  double n_len = std::sqrt(dot(plate->normal, plate->normal));
  Vec3d up = {plate->normal[0] / n_len, plate->normal[1] / n_len, plate->normal[2] / n_len};
  double g_down = -dot(spec.gravity, up);
  if (!(g_down > 0)) throw std::runtime_error(spec.path + ": a drop test needs gravity towards the plate");

  // Release at rest, lowest point H above the plate, above where the case put the body; a
  // clump at a random orientation drawn from the case's seed (one replicate per seed).
  double H = ex.drop_height;
  double plate_level = dot(plate->point, up);
  Vec3d* position = nullptr;
  double lowest = 0;  // of the body as placed, along `up`
  if (clump) {
    BodySpec& body = spec.bodies[0];
    if (options.random_orientation) {
      std::mt19937_64 engine(spec.seed);
      body.orientation = random_orientation([&engine] { return unit_interval(engine()); });
    }
    body.velocity = body.angular_velocity = {0, 0, 0};
    lowest = 1e300;
    for (const SphereSpec& s : body_spheres(body, spec.templates[size_t(body.template_index)]))
      lowest = std::min(lowest, dot(s.position, up) - s.radius);
    position = &body.position;
  } else {
    SphereSpec& body = spec.spheres[0];
    body.velocity = body.angular_velocity = {0, 0, 0};
    lowest = dot(body.position, up) - body.radius;
    position = &body.position;
  }
  for (int k = 0; k < 3; ++k) (*position)[k] += (plate_level + H - lowest) * up[k];

  Model model = build_model(spec);
  uint32_t frame_steps = std::max<uint32_t>(1, uint32_t(std::lround(1.0 / (ex.camera_fps * model.dt))));
  double frame_dt = frame_steps * model.dt;
  Simulation sim(model, make_backend(options.backend, options.device, options.threads, gpu::kDefaultWorkgroup),
                 {}, frame_steps);
  // The camera tracks the body's lowest point; the lift-off test uses its centre's speed.
  auto height = [&](const HostState& s) {
    double low = 1e300;
    for (const auto& p : s.pos) low = std::min(low, dot({p.x, p.y, p.z}, up) - p.w);
    return low - plate_level;
  };
  auto normal_speed = [&](const HostState& s) {
    const gpu::vec4& v = s.bodies.empty() ? s.vel[0] : s.bodies[0].vel;
    return double(v.x) * up[0] + double(v.y) * up[1] + double(v.z) * up[2];
  };

  DropResult r;
  r.drop_height = H;
  r.trajectory.push_back({0.0, height(sim.state())});
  r.wall_forces.sample(sim);
  bool touched = false, left = false;
  double touch_time = 0, prev_speed = 0;
  uint64_t max_frames = uint64_t(ex.max_time / frame_dt) + 1;
  for (uint64_t f = 0; f < max_frames; ++f) {
    sim.advance(frame_steps);
    double h = height(sim.state()), v = normal_speed(sim.state());
    r.trajectory.push_back({sim.time(), h});
    r.wall_forces.sample(sim);
    // A frame below the plate, or (a contact shorter than a frame) the fall turned into a rise.
    if (!touched && (h < 0 || (prev_speed < 0 && v > 0))) {
      touched = true;
      touch_time = sim.time();
      r.impact_speed = -prev_speed;
    }
    if (touched && !left && h > 0 && v > 0) {
      left = true;
      r.contact_time = sim.time() - touch_time;
      r.rebound_height_exact = h + v * v / (2 * g_down);  // free flight from here on
    }
    prev_speed = v;
    if (left && v < 0) break;  // past the apex
  }
  if (!left) throw std::runtime_error(spec.path + ": the body did not rebound within max_time = " +
                                      std::to_string(ex.max_time) + " s");
  // The highest frame after lift-off, refined between its neighbours as camera software does.
  size_t first_after = 0;
  while (r.trajectory[first_after].first <= touch_time) ++first_after;
  size_t best = first_after;
  for (size_t k = first_after; k < r.trajectory.size(); ++k)
    if (r.trajectory[k].second > r.trajectory[best].second) best = k;
  if (best == first_after || best + 1 >= r.trajectory.size()) r.rebound_height = r.trajectory[best].second;
  else r.rebound_height = parabola_peak(r.trajectory[best - 1].second, r.trajectory[best].second,
                                        r.trajectory[best + 1].second);
  r.restitution = std::sqrt(std::max(0.0, r.rebound_height) / H);
  return r;
}

}  // namespace repose
