#include "experiments/drop.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <memory>
#include <stdexcept>

#include "case/body_pose.h"
#include "case/particle_factory.h"
#include "case/time_step.h"
#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "experiments/body_frame.h"
#include "experiments/experiment_simulation.h"
#include "experiments/replicates.h"
#include "util/atomic_file.h"
#include "util/math.h"
#include "util/progress.h"

namespace repose {

namespace {

// Vertex of the parabola through three equally spaced samples (the camera's sub-frame estimate).
double parabola_peak(double a, double b, double c) {
  double denom = a - 2 * b + c;
  if (denom >= 0) return b;
  double offset = 0.5 * (a - c) / denom;
  return b - 0.25 * (a - c) * offset;
}

std::string no_rebound(const CaseSpec& spec) {
  return spec.path + ": the body did not rebound within max_time = " + std::to_string(spec.experiment.max_time) + " s";
}

// The centre of mass's rise from its lowest frame to its highest frame after it, each refined by
// a parabola through its neighbours (the camera's sub-frame estimate).
double centre_rise(const std::vector<double>& z) {
  auto refined = [&](size_t k, double sign) {
    if (k == 0 || k + 1 >= z.size()) return z[k];
    return sign * parabola_peak(sign * z[k - 1], sign * z[k], sign * z[k + 1]);
  };
  size_t bottom = size_t(std::min_element(z.begin(), z.end()) - z.begin());
  size_t top = size_t(std::max_element(z.begin() + std::ptrdiff_t(bottom), z.end()) - z.begin());
  return refined(top, 1.0) - refined(bottom, -1.0);
}

}  // namespace

namespace {

// Places the body (the case's first sphere that is not fixed, else its first such clump) at rest
// with its lowest point `height` above the surface, above where the case put it; a clump at a
// random orientation drawn from the case's seed (one replicate per seed) unless the options say
// otherwise.
void place_body(CaseSpec& spec, const DropSurface& surface, double height, const DropOptions& options) {
  const Vec3d& up = surface.up;
  Vec3d* position = nullptr;
  double lowest = 0;  // of the body as placed, along `up`
  auto sphere = std::find_if(spec.spheres.begin(), spec.spheres.end(), [](const SphereSpec& s) { return !s.fixed; });
  if (sphere == spec.spheres.end()) {
    BodySpec& body = *std::find_if(spec.bodies.begin(), spec.bodies.end(), [](const BodySpec& b) { return !b.fixed; });
    if (options.random_orientation) random_body_orientation(spec, spec.seed);
    body.velocity = body.angular_velocity = {0, 0, 0};
    lowest = 1e300;
    for (const SphereSpec& s : body_spheres(body, spec.templates[size_t(body.template_index)]))
      lowest = std::min(lowest, dot(s.position, up) - s.radius);
    position = &body.position;
  } else {
    SphereSpec& body = *sphere;
    body.velocity = body.angular_velocity = {0, 0, 0};
    lowest = dot(body.position, up) - body.radius;
    position = &body.position;
  }
  for (int k = 0; k < 3; ++k) (*position)[k] += (surface.level + height - lowest) * up[k];
}

// The highest frame after the first touch at touch_time, refined between its neighbours as camera
// software does.
double camera_rebound_height(const std::vector<std::pair<double, double>>& trajectory, double touch_time) {
  size_t first_after = 0;
  while (trajectory[first_after].first <= touch_time) ++first_after;
  size_t best = first_after;
  for (size_t k = first_after; k < trajectory.size(); ++k)
    if (trajectory[k].second > trajectory[best].second) best = k;
  if (best == first_after || best + 1 >= trajectory.size()) return trajectory[best].second;
  return parabola_peak(trajectory[best - 1].second, trajectory[best].second, trajectory[best + 1].second);
}

// The camera's frames of the body's lowest point (particles that move: fixed ones are the rig's),
// until past the rebound's apex; contact and lift-off from the body's speed along `up`.
DropResult film_drop(const CaseSpec& spec, const DropSurface& surface, double g_down, const DropOptions& options) {
  const DropSettings& ex = settings_of<DropSettings>(spec.experiment);
  const Vec3d& up = surface.up;
  Model model = build_model(spec);
  uint32_t frame_steps = std::max<uint32_t>(1, uint32_t(std::lround(1.0 / (ex.camera_fps * model.dt))));
  double frame_dt = frame_steps * model.dt;
  Simulation sim = experiment_simulation(model, options, frame_steps, frame_steps);
  // The run ends past the rebound's apex: before lift-off at most as long again as the fall
  // (a rebound to the release height), after it when the upward speed is spent.
  Progress progress(spec.name + " " + options.label, uint64_t(spec.experiment.max_time / model.dt) + 1, model.dt, options.progress);
  double fall_time = std::sqrt(2 * ex.drop_height / g_down);
  progress.expect_end_time(2 * fall_time, "(at most: a rebound to the release height)");
  auto height = [&](const HostState& s) {
    double low = 1e300;
    for (size_t i = 0; i < s.pos.size(); ++i)
      if (s.vel[i].w != 0.0f) low = std::min(low, dot({s.pos[i].x, s.pos[i].y, s.pos[i].z}, up) - s.pos[i].w);
    return low - surface.level;
  };
  auto normal_speed = [&](const HostState& s) {
    const gpu::vec4& v = s.bodies.empty() ? s.vel[first_moving_sphere(s)] : s.bodies[first_moving_body(s)].vel;
    return double(v.x) * up[0] + double(v.y) * up[1] + double(v.z) * up[2];
  };
  auto centre_height = [&](const HostState& s) { return dot(body_centre(s), up) - surface.level; };
  auto touching = [&](const HostState& s) {  // moving spheres below the surface
    int n = 0;
    for (size_t i = 0; i < s.pos.size(); ++i)
      if (s.vel[i].w != 0.0f && dot({s.pos[i].x, s.pos[i].y, s.pos[i].z}, up) - s.pos[i].w < surface.level) ++n;
    return n;
  };

  DropResult r;
  r.drop_height = ex.drop_height;
  r.trajectory.push_back({0.0, height(sim.state())});
  r.centre_trajectory.push_back(centre_height(sim.state()));
  r.wall_forces.sample(sim);
  bool touched = false, left = false;
  double touch_time = 0, prev_speed = 0;
  uint64_t max_frames = uint64_t(spec.experiment.max_time / frame_dt) + 1;
  for (uint64_t f = 0; f < max_frames; ++f) {
    sim.advance(frame_steps);
    double h = height(sim.state()), v = normal_speed(sim.state());
    r.trajectory.push_back({sim.time(), h});
    r.centre_trajectory.push_back(centre_height(sim.state()));
    if (!left) r.peak_touching = std::max(r.peak_touching, touching(sim.state()));
    r.wall_forces.sample(sim);
    // A frame below the surface, or (a contact shorter than a frame) the fall turned into a rise.
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
    if (left) progress.expect_end_time(sim.time() + std::max(0.0, v) / g_down, "(to the rebound's apex)");
    else if (touched) progress.expect_end_time(std::max(2 * fall_time, sim.time()), "(at most: the body is on the plate)");
    progress.update(sim.step(), printf_text("lowest point %.4g m", h));
    if (left && v < 0) break;  // past the apex
  }
  progress.finish();
  if (!left) {
    if (options.require_rebound) throw std::runtime_error(no_rebound(spec));
    r.rebounded = false;
    return r;
  }
  r.rebound_height = camera_rebound_height(r.trajectory, touch_time);
  r.restitution = std::sqrt(std::max(0.0, r.rebound_height) / ex.drop_height);
  r.centre_rise = centre_rise(r.centre_trajectory);
  return r;
}

}  // namespace

DropOptions drop_options(const ExperimentRunOptions& run, bool require_rebound) {
  DropOptions options;
  static_cast<ExperimentRunOptions&>(options) = run;
  options.require_rebound = require_rebound;
  return options;
}

DropResult drop_onto(const CaseSpec& input, const DropSurface& surface, const DropOptions& options) {
  double g_down = -dot(input.gravity, surface.up);
  if (!(g_down > 0)) throw std::runtime_error(input.path + ": a drop test needs gravity towards the plate");
  CaseSpec spec = input;
  place_body(spec, surface, settings_of<DropSettings>(spec.experiment).drop_height, options);
  return film_drop(spec, surface, g_down, options);
}

DropResult run_drop(const CaseSpec& spec, const DropOptions& options) {
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
  DropSurface surface;
  surface.up = {plate->normal[0] / n_len, plate->normal[1] / n_len, plate->normal[2] / n_len};
  surface.level = dot(plate->point, surface.up);
  return drop_onto(spec, surface, options);
}

void align_impact_phase(CaseSpec& spec) {
  if (spec.spheres.empty() && spec.bodies.empty()) return;
  const Vec3d& gv = spec.gravity;
  double g = std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
  double H = settings_of<DropSettings>(spec.experiment).drop_height;
  if (!(g > 0) || !(H > 0)) return;
  // Fall from rest under gravity and drag k v^2 (per unit mass): t = acosh(exp(k H)) / sqrt(g k).
  // A clump body falls in vacuum (the engine's drag acts on free spheres only) and without
  // turning, so its lowest point meets the plate after sqrt(2 H / g) whatever its orientation.
  double k = 0;
  auto sphere = std::find_if(spec.spheres.begin(), spec.spheres.end(), [](const SphereSpec& s) { return !s.fixed; });
  if (sphere != spec.spheres.end()) {
    const SphereSpec& body = *sphere;
    double r = body.radius;
    double mass = spec.materials.at(body.material).density * 4.0 / 3.0 * kPi * r * r * r;
    k = 0.5 * spec.air_drag.air_density * spec.air_drag.drag_coefficient * kPi * r * r / mass;
  }
  double t_impact = k * H > 1e-9 ? std::acosh(std::exp(k * H)) / std::sqrt(g * k) : std::sqrt(2 * H / g);
  double dt = resolve_dt(spec);
  double steps = std::floor(t_impact / dt);
  if (steps < 10) return;  // a step that long is not a drop simulation anyway
  spec.time.dt = t_impact / (steps + 0.5);
  spec.time.rayleigh_fraction.reset();
}

// ---------------------------------------------------------------------------------------------
// The registered experiment.

std::shared_ptr<const ExperimentSettings> DropExperiment::read_keys(const Section& s) const {
  auto settings = std::make_shared<DropSettings>();
  DropSettings& ex = *settings;
  if (auto h = s.number("drop_height")) {
    ex.drop_height = positive(s, "drop_height", *h);
    if (ex.drop_height > 20) s.fail("drop_height", format_number(*h) + " m is no lab drop: millimetres written as metres?");
  }
  if (auto f = s.number("camera_fps")) ex.camera_fps = positive(s, "camera_fps", *f);
  return settings;
}

std::vector<std::string> DropExperiment::responses() const {
  return {"restitution", "rebound_height", "rebound_height_exact", "contact_time", "impact_speed", "centre_rise"};
}

ExperimentOutcome DropExperiment::outcome(const CaseSpec& spec, const DropResult& r) const {
  ExperimentOutcome o;
  o.values = {{"restitution", r.restitution},   {"rebound_height", r.rebound_height},
              {"rebound_height_exact", r.rebound_height_exact}, {"contact_time", r.contact_time},
              {"impact_speed", r.impact_speed}, {"centre_rise", r.centre_rise}};
  o.trajectory = r.trajectory;
  OrderedJson& j = o.json;
  j["experiment"] = "drop";
  j["case"] = spec.path;
  j["drop_height"] = r.drop_height;
  j["rebound_height"] = r.rebound_height;
  j["rebound_height_exact"] = r.rebound_height_exact;
  j["centre_rise"] = r.centre_rise;
  j["peak_touching"] = r.peak_touching;
  j["restitution"] = r.restitution;
  j["impact_speed"] = r.impact_speed;
  j["contact_time"] = r.contact_time;
  j["camera_fps"] = settings_of<DropSettings>(spec.experiment).camera_fps;
  auto track = std::make_shared<DropResult>(r);
  o.files.push_back(text_file("trajectory.csv", [track](std::ostream& out) {
    out << "t_s,height_m,centre_m\n";
    for (size_t k = 0; k < track->trajectory.size(); ++k)
      out << track->trajectory[k].first << "," << track->trajectory[k].second << "," << track->centre_trajectory[k]
          << "\n";
  }));
  o.lines.push_back(printf_text("drop %s: H = %.4g m, rebound h = %.5g m, e = sqrt(h/H) = %.4f (impact %.3g m/s, contact %.3g ms)",
                                spec.name.c_str(), r.drop_height, r.rebound_height, r.restitution, r.impact_speed,
                                1e3 * r.contact_time));
  auto forces = std::make_shared<WallForceSeries>(r.wall_forces);
  o.files.push_back({"wall_forces.csv", [forces](const std::string& path) {
                       write_file_atomically(path, [&](std::ostream& out) { forces->write_csv(out); });
                     }});
  return o;
}

// Replicates 2..N of a drop: the same case with simulation.seed + k (a clump lands at a new
// random orientation each time); their rebound heights and e go into drop.json with mean and sd.
// A replicate whose body never leaves the plate is recorded as such, and the others go on.
void DropExperiment::add_replicates(ExperimentOutcome& o, const CaseSpec& spec, const ExperimentRun& run,
                                    const DropResult& first) const {
  OrderedJson list = OrderedJson::array();
  std::vector<double> e, h, rise;
  for (int k = 0; k < run.replicates; ++k) {
    CaseSpec replicate = spec;
    replicate.seed = spec.seed + uint64_t(k);
    DropOptions options = drop_options(run, false);
    options.label = printf_text("drop, replicate %d of %d", k + 1, run.replicates);
    options.frames.name += printf_text("_replicate%d", k + 1);
    DropResult r = k == 0 ? first : drop(replicate, options);
    if (!r.rebounded) {
      list.push_back({{"seed", replicate.seed}, {"problem", no_rebound(replicate)}});
      o.lines.push_back(printf_text("  replicate %d (seed %llu): no rebound within max_time = %g s", k + 1,
                                    (unsigned long long)replicate.seed, replicate.experiment.max_time));
      continue;
    }
    e.push_back(r.restitution);
    h.push_back(r.rebound_height);
    rise.push_back(r.centre_rise);
    list.push_back({{"seed", replicate.seed}, {"rebound_height", r.rebound_height}, {"restitution", r.restitution},
                    {"centre_rise", r.centre_rise}, {"peak_touching", r.peak_touching}});
    o.lines.push_back(printf_text("  replicate %d (seed %llu): h = %.5g m, e = %.4f, centre rise %.5g m", k + 1,
                                  (unsigned long long)replicate.seed, r.rebound_height, r.restitution, r.centre_rise));
  }
  auto [e_mean, e_sd] = mean_sd(e);
  auto [h_mean, h_sd] = mean_sd(h);
  auto [rise_mean, rise_sd] = mean_sd(rise);
  o.lines.push_back(printf_text("  e over %zu of %d replicates: mean %.4f, sd %.4f; h mean %.5g m, sd %.3g; centre rise "
                                "mean %.5g m, sd %.3g",
                                e.size(), run.replicates, e_mean, e_sd, h_mean, h_sd, rise_mean, rise_sd));
  o.json["replicates"] = {{"runs", list},
                          {"counted", e.size()},
                          {"restitution_mean", e_mean},
                          {"restitution_sd", e_sd},
                          {"rebound_height_mean", h_mean},
                          {"rebound_height_sd", h_sd},
                          {"centre_rise_mean", rise_mean},
                          {"centre_rise_sd", rise_sd}};
}

ExperimentOutcome DropExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  DropOptions options = drop_options(run, run.strict);
  if (run.replicates > 1) {
    options.label = printf_text("drop, replicate 1 of %d", run.replicates);
    options.frames.name += "_replicate1";
  }
  DropResult r = drop(spec, options);
  ExperimentOutcome o = outcome(spec, r);
  if (!r.rebounded) {
    o.status = OutcomeStatus::NoRebound;
    o.problem = no_rebound(spec);
    o.lines.clear();
    return o;
  }
  if (run.replicates > 1) add_replicates(o, spec, run, r);
  return o;
}

const DiagnosisRole* DropExperiment::diagnosis() const {
  static const DiagnosisRole role = [] {
    DiagnosisRole r;
    r.measures = {{"rebound_height", false, "m"}, {"restitution", false, "1"}, {"height", true, "m"}};
    r.synthetic = {"rebound_height"};
    r.baseline = {"restitution", "1", 0.05, 0.95, false};
    r.baseline_field = &Interaction::restitution;
    r.baseline_model = "Hertz-Mindlin, constant restitution";
    r.condition = "experiment.drop_height";
    r.truth_option = "restitution";
    r.separating = SeparatingMeasurement::CameraTrack;
    return r;
  }();
  return &role;
}

// The body (its first sphere, else its first clump) and the plate, the first plane wall.
Interaction& DropExperiment::tested_contact(CaseSpec& spec) const {
  int a = 0;
  if (!spec.spheres.empty()) a = spec.spheres[0].material;
  else if (!spec.bodies.empty()) a = spec.bodies[0].material;
  else throw std::runtime_error(spec.path + ": the case has no body");
  auto plate = std::find_if(spec.walls.begin(), spec.walls.end(),
                            [](const WallSpec& w) { return w.type == WallSpec::Type::Plane; });
  if (plate == spec.walls.end()) throw std::runtime_error(spec.path + ": the case has no plane wall (plate)");
  return interaction_between(spec, a, plate->material, "the body and the plate");
}

std::string DropExperiment::diagnosis_problem(const CaseSpec& spec) const {
  if (spec.bodies.empty() && spec.spheres.size() == 1) return "";
  return "diagnose drops one sphere (a clump body is what the `shape` extension tests; the other extensions' drop "
         "physics and the impact-time alignment are written for a sphere)";
}

DiagnosticOutcome DropExperiment::simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>&,
                                                         bool strict) const {
  double g = std::sqrt(dot(spec.gravity, spec.gravity));
  double H = settings_of<DropSettings>(spec.experiment).drop_height;
  if (!strict) {
    // A search meets models that stop the body on the plate: no need to wait long for them.
    double fall = std::sqrt(2 * H / g);
    spec.experiment.max_time = std::min(spec.experiment.max_time, 3 * fall + 0.5);
  }
  align_impact_phase(spec);
  DropOptions options;
  options.require_rebound = strict;
  DropResult r = drop(spec, options);
  DiagnosticOutcome out;
  if (!r.rebounded) {
    // Predict no rebound, a fall in vacuum and rest, so the search moves away from such models.
    out.values = {{"rebound_height", 0}, {"restitution", 0}};
    for (int k = 0; k <= 100; ++k) {
      double t = k * 0.01 * spec.experiment.max_time;
      out.trajectory.push_back({t, std::max(0.0, H - 0.5 * g * t * t)});
    }
    return out;
  }
  out.values = {{"rebound_height", r.rebound_height}, {"restitution", r.restitution}};
  out.trajectory = std::move(r.trajectory);
  return out;
}

// Lengths a thousand times the rig's size are millimetres written as metres; a rebound above the
// release or a restitution outside (0, 1] cannot be measured.
std::string DropExperiment::implausible(const MeasureInfo& m, double value, const CaseSpec& spec) const {
  if (m.name == "restitution" && !(value > 0 && value <= 1)) return "a restitution coefficient lies in (0, 1]";
  if (m.unit != "m") return "";
  double H = settings_of<DropSettings>(spec.experiment).drop_height;
  if (value > 10 * H)
    return std::to_string(value) + " m is more than ten times the drop height " + std::to_string(H) +
           " m: millimetres? Values are in SI units (m)";
  if (m.name == "rebound_height" && value > H)
    return std::to_string(value) + " m is higher than the drop height " + std::to_string(H) +
           " m: a body does not rebound above its release (e > 1)";
  return "";
}

const Experiment& drop_experiment() {
  static const DropExperiment drop;
  return drop;
}

}  // namespace repose
