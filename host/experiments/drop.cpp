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
#include "util/atomic_file.h"

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

std::string no_rebound(const CaseSpec& spec) {
  return spec.path + ": the body did not rebound within max_time = " + std::to_string(spec.experiment.max_time) + " s";
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
  bool touched = false, left = false;
  double touch_time = 0, prev_speed = 0;
  uint64_t max_frames = uint64_t(ex.max_time / frame_dt) + 1;
  for (uint64_t f = 0; f < max_frames; ++f) {
    sim.advance(frame_steps);
    double h = height(sim.state()), v = normal_speed(sim.state());
    r.trajectory.push_back({sim.time(), h});
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
  if (!left) {
    if (options.require_rebound) throw std::runtime_error(no_rebound(spec));
    r.rebounded = false;
    return r;
  }
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

void align_impact_phase(CaseSpec& spec) {
  if (spec.spheres.empty() && spec.bodies.empty()) return;
  constexpr double kPi = 3.14159265358979323846;
  const Vec3d& gv = spec.gravity;
  double g = std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
  double H = spec.experiment.drop_height;
  if (!(g > 0) || !(H > 0)) return;
  // Fall from rest under gravity and drag k v^2 (per unit mass): t = acosh(exp(k H)) / sqrt(g k).
  // A clump body falls in vacuum (the engine's drag acts on free spheres only) and without
  // turning, so its lowest point meets the plate after sqrt(2 H / g) whatever its orientation.
  double k = 0;
  if (!spec.spheres.empty()) {
    const SphereSpec& body = spec.spheres[0];
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

void DropExperiment::read_keys(const Section& s, ExperimentSpec& ex) const {
  if (auto h = s.number("drop_height")) ex.drop_height = positive(s, "drop_height", *h);
  if (auto f = s.number("camera_fps")) ex.camera_fps = positive(s, "camera_fps", *f);
}

std::vector<std::string> DropExperiment::responses() const {
  return {"restitution", "rebound_height", "rebound_height_exact", "contact_time", "impact_speed"};
}

ExperimentOutcome DropExperiment::outcome(const CaseSpec& spec, const DropResult& r) const {
  ExperimentOutcome o;
  o.values = {{"restitution", r.restitution},   {"rebound_height", r.rebound_height},
              {"rebound_height_exact", r.rebound_height_exact}, {"contact_time", r.contact_time},
              {"impact_speed", r.impact_speed}};
  o.trajectory = r.trajectory;
  OrderedJson& j = o.json;
  j["experiment"] = "drop";
  j["case"] = spec.path;
  j["drop_height"] = r.drop_height;
  j["rebound_height"] = r.rebound_height;
  j["rebound_height_exact"] = r.rebound_height_exact;
  j["restitution"] = r.restitution;
  j["impact_speed"] = r.impact_speed;
  j["contact_time"] = r.contact_time;
  j["camera_fps"] = spec.experiment.camera_fps;
  auto track = std::make_shared<std::vector<std::pair<double, double>>>(r.trajectory);
  o.files.push_back({"trajectory.csv", [track](const std::string& path) {
                       write_file_atomically(path, [&](std::ostream& out) {
                         out << "t,height\n";
                         for (const auto& [t, h] : *track) out << t << "," << h << "\n";
                       });
                     }});
  o.lines.push_back(printf_text("drop %s: H = %.4g m, rebound h = %.5g m, e = sqrt(h/H) = %.4f (impact %.3g m/s, contact %.3g ms)",
                                spec.name.c_str(), r.drop_height, r.rebound_height, r.restitution, r.impact_speed,
                                1e3 * r.contact_time));
  o.written = [](const std::string& dir) { return "wrote " + dir + "/drop.json and " + dir + "/trajectory.csv"; };
  return o;
}

// Replicates 2..N of a drop: the same case with simulation.seed + k (a clump lands at a new
// random orientation each time); their rebound heights and e go into drop.json with mean and sd.
void DropExperiment::add_replicates(ExperimentOutcome& o, const CaseSpec& spec, const ExperimentRun& run,
                                    const DropResult& first) const {
  OrderedJson list = OrderedJson::array();
  std::vector<double> e;
  for (int k = 0; k < run.replicates; ++k) {
    CaseSpec replicate = spec;
    replicate.seed = spec.seed + uint64_t(k);
    DropResult r = k == 0 ? first : drop(replicate, {run.backend, run.device, run.threads});
    e.push_back(r.restitution);
    list.push_back({{"seed", replicate.seed}, {"rebound_height", r.rebound_height}, {"restitution", r.restitution}});
    o.lines.push_back(printf_text("  replicate %d (seed %llu): h = %.5g m, e = %.4f", k + 1,
                                  (unsigned long long)replicate.seed, r.rebound_height, r.restitution));
  }
  double mean = 0, var = 0;
  for (double x : e) mean += x / double(e.size());
  for (double x : e) var += (x - mean) * (x - mean) / double(std::max<size_t>(1, e.size() - 1));
  o.lines.push_back(printf_text("  e over %d replicates: mean %.4f, sd %.4f", run.replicates, mean, std::sqrt(var)));
  o.json["replicates"] = {{"runs", list}, {"restitution_mean", mean}, {"restitution_sd", std::sqrt(var)}};
}

ExperimentOutcome DropExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  DropOptions options{run.backend, run.device, run.threads};
  options.require_rebound = run.strict;
  DropResult r = drop(spec, options);
  if (!r.rebounded) {
    ExperimentOutcome o;
    o.status = OutcomeStatus::NoRebound;
    o.problem = no_rebound(spec);
    o.trajectory = r.trajectory;
    return o;
  }
  ExperimentOutcome o = outcome(spec, r);
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
  if (!strict) {
    // A search meets models that stop the body on the plate: no need to wait long for them.
    double fall = std::sqrt(2 * spec.experiment.drop_height / g);
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
      out.trajectory.push_back({t, std::max(0.0, spec.experiment.drop_height - 0.5 * g * t * t)});
    }
    return out;
  }
  out.values = {{"rebound_height", r.rebound_height}, {"restitution", r.restitution}};
  out.trajectory = std::move(r.trajectory);
  return out;
}

// Lengths a thousand times the rig's size are millimetres written as metres.
std::string DropExperiment::implausible(const MeasureInfo& m, double value, const CaseSpec& spec) const {
  if (m.unit != "m" || !(value > 10 * spec.experiment.drop_height)) return "";
  return std::to_string(value) + " m is more than ten times the drop height " +
         std::to_string(spec.experiment.drop_height) + " m: millimetres? Values are in SI units (m)";
}

const Experiment& drop_experiment() {
  static const DropExperiment drop;
  return drop;
}

}  // namespace repose
