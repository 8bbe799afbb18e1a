#include "experiments/drop.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
  if (spec.spheres.size() != 1)
    throw std::runtime_error(spec.path + ": a drop test needs exactly one body; the case has " +
                             std::to_string(spec.spheres.size()) + " particles");
  auto plate = std::find_if(spec.walls.begin(), spec.walls.end(),
                            [](const WallSpec& w) { return w.type == WallSpec::Type::Plane; });
  if (plate == spec.walls.end())
    throw std::runtime_error(spec.path + ": a drop test needs a plane [[wall]] as the plate");
  double n_len = std::sqrt(dot(plate->normal, plate->normal));
  Vec3d up = {plate->normal[0] / n_len, plate->normal[1] / n_len, plate->normal[2] / n_len};
  double g_down = -dot(spec.gravity, up);
  if (!(g_down > 0)) throw std::runtime_error(spec.path + ": a drop test needs gravity towards the plate");

  // Release at rest, lowest point H above the plate, above where the case put the body.
  SphereSpec& body = spec.spheres[0];
  double R = body.radius, H = ex.drop_height;
  double lateral = dot(body.position, up) - dot(plate->point, up);
  for (int k = 0; k < 3; ++k)
    body.position[k] = body.position[k] - lateral * up[k] + (H + R) * up[k];
  body.velocity = {0, 0, 0};
  body.angular_velocity = {0, 0, 0};

  Model model = build_model(spec);
  uint32_t frame_steps = std::max<uint32_t>(1, uint32_t(std::lround(1.0 / (ex.camera_fps * model.dt))));
  double frame_dt = frame_steps * model.dt;
  Simulation sim(model, make_backend(options.backend, options.device, options.threads, gpu::kDefaultWorkgroup),
                 {}, frame_steps);
  auto height = [&](const HostState& s) {
    Vec3d x = {s.pos[0].x, s.pos[0].y, s.pos[0].z};
    return dot(x, up) - dot(plate->point, up) - R;
  };
  auto normal_speed = [&](const HostState& s) {
    return double(s.vel[0].x) * up[0] + double(s.vel[0].y) * up[1] + double(s.vel[0].z) * up[2];
  };

  DropResult r;
  r.drop_height = H;
  r.trajectory.push_back({0.0, height(sim.state())});
  bool touched = false, left = false;
  double touch_time = 0, prev_speed = 0;
  uint64_t max_frames = uint64_t(ex.max_time / frame_dt) + 1;
  for (uint64_t f = 0; f < max_frames; ++f) {
    sim.advance(frame_steps);
    double h = height(sim.state()), v = normal_speed(sim.state());
    r.trajectory.push_back({sim.time(), h});
    if (!touched && h < 0) {
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
