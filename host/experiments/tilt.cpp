#include "experiments/experiment_simulation.h"
#include "experiments/tilt.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "experiments/body_frame.h"
#include "util/atomic_file.h"
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

TiltResult run_tilt(const CaseSpec& input, const ExperimentRunOptions& options, bool require_motion) {
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
  uint64_t sample_steps = steps_in(sample_dt, model.dt);
  double end_time = std::min(ex.max_time, plate.motion.stop_time);
  uint64_t total_steps = uint64_t(end_time / model.dt) + 1;
  Simulation sim = experiment_simulation(model, options, sample_steps, 500);
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
  Vec3d turned{0, 0, 0};  // the first body's rotation since the tilt began (w dt summed: rocking cancels)
  // Its rolling radius: the lowest point of the body below its centre at rest.
  double rolling_radius = 0;
  const Vec3d up = plate.normal;
  {
    Vec3d c = body_centre(sim.state());
    for (const auto& p : sim.state().pos)
      rolling_radius = std::max(rolling_radius, dot(sub(c, {p.x, p.y, p.z}), up) + p.w);
  }
  TiltSample previous{sim.time(), 0, 0};
  double previous_speed = 0;
  r.trajectory.push_back(previous);
  r.wall_forces.sample(sim);
  while (true) {
    if (sim.time() >= end_time) {
      if (require_motion)
        throw std::runtime_error(spec.path + ": the body did not move by " +
                                 (ex.onset_speed > 0 ? "a speed of " + std::to_string(ex.onset_speed) + " m/s"
                                                     : std::to_string(ex.onset_distance) + " m") +
                                 " up to a tilt of " + std::to_string(rate * (sim.time() - ex.settle_time) * 180 / kPi) +
                                 " degrees (max_angle, max_time)");
      r.moved = false;
      break;
    }
    sim.advance(sample_steps);
    Vec3d w = first_body_spin(sim.state());
    for (int k = 0; k < 3; ++k) turned[k] += w[k] * double(sample_steps) * model.dt;
    // Along the plate only: the body still sinks into the plate (Hertz) while it settles.
    Vec3d moved = sub(in_plate_frame(body_centre(sim.state()), sim.time()), start);
    double sink = dot(moved, up);
    Vec3d along = {moved[0] - sink * up[0], moved[1] - sink * up[1], moved[2] - sink * up[2]};
    TiltSample s{sim.time(), rate * (sim.time() - ex.settle_time) * 180 / kPi, std::sqrt(dot(along, along))};
    r.trajectory.push_back(s);
    r.wall_forces.sample(sim);
    progress.update(sim.step(), "tilt " + std::to_string(s.angle_deg).substr(0, 5) + " deg");
    // Speed relative to the plate over the last sample interval.
    double speed = (s.displacement - previous.displacement) / (s.time - previous.time);
    bool moving = ex.onset_speed > 0 ? speed >= ex.onset_speed : s.displacement >= ex.onset_distance;
    if (moving) {
      // Where the criterion was met, between the two samples: the displacement crossing its
      // threshold, or the speed (an interval's mean, taken at its middle) crossing its.
      double f = ex.onset_speed > 0
                     ? std::clamp((ex.onset_speed - previous_speed) / (speed - previous_speed), 0.0, 1.0) - 0.5
                     : (ex.onset_distance - previous.displacement) / (s.displacement - previous.displacement);
      r.onset_angle_deg = previous.angle_deg + f * (s.angle_deg - previous.angle_deg);
      r.onset_time = previous.time + f * (s.time - previous.time);
      // Relative to the plate, which turned the body with it.
      double tilt = rate * (sim.time() - ex.settle_time);
      Vec3d own = {turned[0] - tilt * ex.tilt_axis[0], turned[1] - tilt * ex.tilt_axis[1], turned[2] - tilt * ex.tilt_axis[2]};
      r.rolled_fraction = std::sqrt(dot(own, own)) * rolling_radius / s.displacement;
      break;
    }
    previous = s;
    previous_speed = speed;
  }
  progress.finish();
  r.tan_alpha = std::tan(r.onset_angle_deg * kPi / 180);
  return r;
}

std::vector<std::string> tilt_keys() {
  return {"plate", "tilt_rate", "tilt_axis", "settle_time", "onset_distance", "onset_speed", "max_angle"};
}

void read_tilt_keys(const Section& s, ExperimentSpec& ex) {
  ex.plate = s.text("plate").value_or("");
  if (auto r = s.number("tilt_rate")) ex.tilt_rate_deg = positive(s, "tilt_rate", *r);
  if (auto a = s.vector3("tilt_axis")) ex.tilt_axis = unit_vector(s, "tilt_axis", *a);
  if (auto t = s.number("settle_time")) ex.settle_time = non_negative(s, "settle_time", *t);
  if (auto d = s.number("onset_distance")) ex.onset_distance = positive(s, "onset_distance", *d);
  if (auto v = s.number("onset_speed")) ex.onset_speed = non_negative(s, "onset_speed", *v);
  if (auto a = s.number("max_angle")) {
    if (!(*a > 0 && *a < 90)) s.fail("max_angle", format_number(*a) + " must lie between 0 and 90 degrees");
    ex.max_angle_deg = *a;
  }
}

// ---------------------------------------------------------------------------------------------
// The registered experiments.

std::vector<std::string> TiltExperiment::responses() const {
  return {"onset_angle_deg", "tan_alpha", "onset_time", "rolled_fraction"};
}

ExperimentOutcome TiltExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  auto r = std::make_shared<TiltResult>(run_tilt(spec, run, run.strict));
  ExperimentOutcome o;
  if (!r->moved) {
    o.status = OutcomeStatus::DidNotMove;
    o.problem = spec.path + ": the body did not move up to max_angle = " + format_number(spec.experiment.max_angle_deg) +
                " degrees (or max_time)";
    return o;
  }
  o.values = {{"onset_angle_deg", r->onset_angle_deg}, {"tan_alpha", r->tan_alpha}, {"onset_time", r->onset_time},
              {"rolled_fraction", r->rolled_fraction}};
  OrderedJson& j = o.json;
  j["experiment"] = spec.experiment.type;
  j["method"] = "tilt";
  j["case"] = spec.path;
  j["tilt_rate_deg_per_s"] = spec.experiment.tilt_rate_deg;
  j["onset_distance"] = spec.experiment.onset_distance;
  j["onset_angle_deg"] = r->onset_angle_deg;
  j["onset_time"] = r->onset_time;
  j[quantity_] = r->tan_alpha;
  j["rolled_fraction"] = r->rolled_fraction;
  o.files.push_back({"trajectory.csv", [r](const std::string& path) {
                       write_file_atomically(path, [&](std::ostream& out) {
                         out << "t,angle_deg,displacement\n";
                         for (const auto& s : r->trajectory) out << s.time << "," << s.angle_deg << "," << s.displacement << "\n";
                       });
                     }});
  if (!r->wall_forces.rows.empty())
    o.files.push_back({"wall_forces.csv", [r](const std::string& path) {
                         write_file_atomically(path, [&](std::ostream& out) { r->wall_forces.write_csv(out); });
                       }});
  o.lines.push_back(printf_text("%s %s: the body starts to %s at alpha = %.3f deg, %s = tan(alpha) = %.4f (rolled fraction %.2f)",
                                type_.c_str(), spec.name.c_str(), motion_.c_str(), r->onset_angle_deg, quantity_.c_str(),
                                r->tan_alpha, r->rolled_fraction));
  std::string type = type_;
  o.written = [type](const std::string& dir) { return "wrote " + dir + "/" + type + ".json, trajectory.csv, wall_forces.csv"; };
  return o;
}

Interaction& body_plate_contact(CaseSpec& spec) {
  int a = 0;
  if (!spec.spheres.empty()) a = spec.spheres[0].material;
  else if (!spec.bodies.empty()) a = spec.bodies[0].material;
  else throw std::runtime_error(spec.path + ": the case has no body");
  const WallSpec& plate = spec.walls.at(find_wall(spec, spec.experiment.plate, "plate"));
  return interaction_between(spec, a, plate.material, "the body and the plate");
}

std::string one_body_problem(const CaseSpec& spec) {
  bool one_body = spec.fills.empty() && spec.lattices.empty() &&
                  ((spec.spheres.size() == 1 && spec.bodies.empty()) || (spec.spheres.empty() && spec.bodies.size() == 1));
  return one_body ? "" : "diagnose tilts or rolls one body (one [[sphere]] or one [[clump]], no fills or lattices)";
}

Interaction& TiltExperiment::tested_contact(CaseSpec& spec) const { return body_plate_contact(spec); }

std::string TiltExperiment::diagnosis_problem(const CaseSpec& spec) const { return one_body_problem(spec); }

DiagnosticOutcome TiltExperiment::simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>&,
                                                         bool strict) const {
  TiltResult r = run_tilt(spec, {}, strict);
  // The body held on up to max_angle: predict max_angle, the most the rig can tell.
  double angle = r.moved ? r.onset_angle_deg : spec.experiment.max_angle_deg;
  return {{{role_.measures.front().name, angle}}, {}};
}

const Experiment& slide_experiment() {
  static const TiltExperiment slide("slide", "slide", "slide", "mu_s", [] {
    DiagnosisRole r;
    r.measures = {{"slide_angle", false, "deg"}};
    r.synthetic = {"slide_angle"};
    r.baseline = {"static_friction", "1", 0.05, 1.2, false};
    r.baseline_field = &Interaction::static_friction;
    r.baseline_model = "Hertz-Mindlin, Coulomb friction, no cohesion";
    r.condition = "material.0.density";
    r.truth_option = "plate_friction";
    return r;
  }());
  return slide;
}

}  // namespace repose
