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
#include "util/math.h"

namespace repose {

namespace {

// The plate's motion replaced by the tilt: about tilt_axis through its point at tilt_rate after
// settle_time, up to max_angle. Returns the plate.
const WallSpec& set_tilt(CaseSpec& spec) {
  const TiltSettings& ex = settings_of<TiltSettings>(spec.experiment);
  WallSpec& plate = spec.walls[find_wall(spec, ex.plate, "tilting plate")];
  if (plate.type != WallSpec::Type::Rectangle && plate.type != WallSpec::Type::Plane)
    throw std::runtime_error(spec.path + ": the tilting plate '" + plate.name + "' must be a rectangle or a plane");
  double rate = ex.tilt_rate_deg * kPi / 180.0;
  plate.motion = WallMotion{};
  plate.motion.rotation_axis_point = plate.point;
  plate.motion.rotation_axis = ex.tilt_axis;
  plate.motion.angular_rate = rate;
  plate.motion.start_time = ex.settle_time;
  plate.motion.stop_time = ex.settle_time + ex.max_angle_deg * kPi / 180.0 / rate;
  return plate;
}

// The body on the tilting plate, sample by sample: its displacement along the plate, relative
// to the plate (rotated back by the tilt so far, exactly, in double), and its turn since the
// tilt began (w dt summed: rocking cancels).
struct TiltTracker {
  const TiltSettings& ex;
  Vec3d pivot, up;
  double rate, rolling_radius = 0;
  Vec3d start{0, 0, 0}, turned{0, 0, 0};

  TiltTracker(const TiltSettings& e, const WallSpec& plate, const HostState& at_rest, double time)
      : ex(e), pivot(plate.point), up(plate.normal), rate(plate.motion.angular_rate) {
    start = in_plate_frame(body_centre(at_rest), time);
    // The rolling radius: the lowest point of the body below its centre at rest.
    Vec3d c = body_centre(at_rest);
    for (const auto& p : at_rest.pos) rolling_radius = std::max(rolling_radius, dot(sub(c, {p.x, p.y, p.z}), up) + p.w);
  }
  double tilt(double t) const { return rate * std::max(0.0, t - ex.settle_time); }
  Vec3d in_plate_frame(Vec3d x, double t) const { return rotate_about(sub(x, pivot), ex.tilt_axis, -tilt(t)); }

  TiltSample sample(const HostState& s, double t, uint64_t steps, double dt) {
    Vec3d w = first_body_spin(s);
    for (int k = 0; k < 3; ++k) turned[k] += w[k] * double(steps) * dt;
    // Along the plate only: the body still sinks into the plate (Hertz) while it settles.
    Vec3d moved = sub(in_plate_frame(body_centre(s), t), start);
    double sink = dot(moved, up);
    Vec3d along = {moved[0] - sink * up[0], moved[1] - sink * up[1], moved[2] - sink * up[2]};
    return {t, rate * (t - ex.settle_time) * 180 / kPi, std::sqrt(dot(along, along))};
  }
  // The body's own turn (the plate turned it with it) x rolling radius / displacement.
  double rolled_fraction(const TiltSample& s) const {
    double a = tilt(s.time);
    Vec3d own = {turned[0] - a * ex.tilt_axis[0], turned[1] - a * ex.tilt_axis[1], turned[2] - a * ex.tilt_axis[2]};
    return std::sqrt(dot(own, own)) * rolling_radius / s.displacement;
  }
};

// Where the onset criterion was met between samples a and b: the displacement crossing its
// threshold, or the speed (an interval's mean, taken at its middle) crossing its; a fraction of
// the interval.
double onset_fraction(const TiltSettings& ex, const TiltSample& a, const TiltSample& b, double speed_a, double speed_b) {
  if (ex.onset_speed > 0) return std::clamp((ex.onset_speed - speed_a) / (speed_b - speed_a), 0.0, 1.0) - 0.5;
  return (ex.onset_distance - a.displacement) / (b.displacement - a.displacement);
}

std::string no_motion_message(const CaseSpec& spec, double angle_deg) {
  const TiltSettings& ex = settings_of<TiltSettings>(spec.experiment);
  return spec.path + ": the body did not move by " +
         (ex.onset_speed > 0 ? "a speed of " + std::to_string(ex.onset_speed) + " m/s"
                             : std::to_string(ex.onset_distance) + " m") +
         " up to a tilt of " + std::to_string(angle_deg) + " degrees (max_angle, max_time)";
}

}  // namespace

TiltResult run_tilt(const CaseSpec& input, const ExperimentRunOptions& options, bool require_motion,
                    double expected_onset_deg) {
  CaseSpec spec = input;
  const TiltSettings& ex = settings_of<TiltSettings>(spec.experiment);
  const WallSpec& plate = set_tilt(spec);
  double rate = plate.motion.angular_rate;
  Model model = build_model(spec);
  double sample_dt = std::min(0.01, 0.05 * kPi / 180.0 / rate);  // every 0.05 degrees at most
  uint64_t sample_steps = steps_in(sample_dt, model.dt);
  double end_time = std::min(spec.experiment.max_time, plate.motion.stop_time);
  Simulation sim = experiment_simulation(model, options, sample_steps, 500);
  Progress progress(spec.name + " " + spec.experiment.type, uint64_t(end_time / model.dt) + 1, model.dt, options.progress);
  // The onset is expected about a degree past atan(coefficient) (README, the slide curve); once
  // the plate is past that, the run ends at the latest at max_angle.
  double expected_onset_time = expected_onset_deg > 0 ? ex.settle_time + (expected_onset_deg + 1) / ex.tilt_rate_deg : -1;
  auto expect = [&](double t) {
    if (t < expected_onset_time) progress.expect_end_time(expected_onset_time, printf_text("(onset expected near %.1f deg)", expected_onset_deg + 1));
    else progress.expect_end_time(end_time, "(up to max_angle)");
  };
  expect(0);

  TiltResult r;
  sim.advance(uint64_t(std::llround(ex.settle_time / model.dt)),
              [&](const Simulation& s) { progress.update(s.step(), "settling before the tilt"); });
  TiltTracker body(ex, plate, sim.state(), sim.time());
  TiltSample previous{sim.time(), 0, 0};
  double previous_speed = 0;
  bool moved = false;
  r.trajectory.push_back(previous);
  r.wall_forces.sample(sim);
  while (sim.time() < end_time) {
    sim.advance(sample_steps);
    TiltSample s = body.sample(sim.state(), sim.time(), sample_steps, model.dt);
    r.trajectory.push_back(s);
    r.wall_forces.sample(sim);
    expect(sim.time());
    progress.update(sim.step(), printf_text("tilt %.2f deg, moved %.3g mm", s.angle_deg, 1e3 * s.displacement));
    // Speed relative to the plate over the last sample interval.
    double speed = (s.displacement - previous.displacement) / (s.time - previous.time);
    if (ex.onset_speed > 0 ? speed >= ex.onset_speed : s.displacement >= ex.onset_distance) {
      double f = onset_fraction(ex, previous, s, previous_speed, speed);
      r.onset_angle_deg = previous.angle_deg + f * (s.angle_deg - previous.angle_deg);
      r.onset_time = previous.time + f * (s.time - previous.time);
      r.rolled_fraction = body.rolled_fraction(s);
      moved = true;
      break;
    }
    previous = s;
    previous_speed = speed;
  }
  if (!moved) {
    if (require_motion) throw std::runtime_error(no_motion_message(spec, rate * (sim.time() - ex.settle_time) * 180 / kPi));
    r.moved = false;
  }
  progress.finish();
  r.tan_alpha = std::tan(r.onset_angle_deg * kPi / 180);
  return r;
}

std::vector<std::string> tilt_keys() {
  return {"plate", "tilt_rate", "tilt_axis", "settle_time", "onset_distance", "onset_speed", "max_angle"};
}

void read_tilt_keys(const Section& s, TiltSettings& ex) {
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

std::shared_ptr<const ExperimentSettings> TiltExperiment::read_keys(const Section& s) const {
  auto settings = std::make_shared<TiltSettings>();
  read_tilt_keys(s, *settings);
  return settings;
}

std::vector<std::string> TiltExperiment::responses() const {
  return {"onset_angle_deg", "tan_alpha", "onset_time", "rolled_fraction"};
}

// atan of the tested contact's coefficient, in degrees; -1 when the case names no such contact.
double TiltExperiment::expected_onset_deg(const CaseSpec& spec) const {
  CaseSpec probe = spec;
  try {
    double coefficient = tested_contact(probe).*role_.baseline_field;
    return coefficient > 0 ? std::atan(coefficient) * 180 / kPi : -1;
  } catch (const std::runtime_error&) {
    return -1;
  }
}

ExperimentOutcome TiltExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  auto r = std::make_shared<TiltResult>(run_tilt(spec, run, run.strict, expected_onset_deg(spec)));
  const TiltSettings& ex = settings_of<TiltSettings>(spec.experiment);
  ExperimentOutcome o;
  if (!r->moved) {
    o.status = OutcomeStatus::DidNotMove;
    o.problem = spec.path + ": the body did not move up to max_angle = " + format_number(ex.max_angle_deg) +
                " degrees (or max_time)";
  }
  o.values = {{"onset_angle_deg", r->onset_angle_deg}, {"tan_alpha", r->tan_alpha}, {"onset_time", r->onset_time},
              {"rolled_fraction", r->rolled_fraction}};
  OrderedJson& j = o.json;
  j["experiment"] = spec.experiment.type;
  j["method"] = "tilt";
  j["case"] = spec.path;
  j["tilt_rate_deg_per_s"] = ex.tilt_rate_deg;
  // The onset criterion the case used: a speed relative to the plate, or a displacement along it.
  if (ex.onset_speed > 0) j["onset_speed"] = ex.onset_speed;
  else j["onset_distance"] = ex.onset_distance;
  if (r->moved) {
    j["onset_angle_deg"] = r->onset_angle_deg;
    j["onset_time"] = r->onset_time;
    j[quantity_] = r->tan_alpha;
    j["rolled_fraction"] = r->rolled_fraction;
  } else {
    j["largest_angle_deg"] = r->trajectory.empty() ? 0.0 : r->trajectory.back().angle_deg;
  }
  o.files.push_back(text_file("trajectory.csv", [r](std::ostream& out) {
    out << "t_s,angle_deg,displacement_m\n";
    for (const auto& s : r->trajectory) out << s.time << "," << s.angle_deg << "," << s.displacement << "\n";
  }));
  if (!r->wall_forces.rows.empty())
    o.files.push_back(text_file("wall_forces.csv", [r](std::ostream& out) { r->wall_forces.write_csv(out); }));
  if (r->moved)
    o.lines.push_back(printf_text("%s %s: the body starts to %s at alpha = %.3f deg, %s = tan(alpha) = %.4f (rolled fraction %.2f)",
                                  type_.c_str(), spec.name.c_str(), motion_.c_str(), r->onset_angle_deg, quantity_.c_str(),
                                  r->tan_alpha, r->rolled_fraction));
  return o;
}

Interaction& body_plate_contact(CaseSpec& spec) {
  int a = 0;
  if (!spec.spheres.empty()) a = spec.spheres[0].material;
  else if (!spec.bodies.empty()) a = spec.bodies[0].material;
  else throw std::runtime_error(spec.path + ": the case has no body");
  const WallSpec& plate = spec.walls.at(find_wall(spec, settings_of<TiltSettings>(spec.experiment).plate, "plate"));
  return interaction_between(spec, a, plate.material, "the body and the plate");
}

std::string one_body_problem(const CaseSpec& spec) {
  bool one_body = spec.fills.empty() && spec.lattices.empty() &&
                  ((spec.spheres.size() == 1 && spec.bodies.empty()) || (spec.spheres.empty() && spec.bodies.size() == 1));
  return one_body ? "" : "diagnose tilts or rolls one body (one [[sphere]] or one [[clump]], no fills or lattices)";
}

DiagnosisRole body_plate_role(MeasureInfo measure, FreeParameter baseline, double Interaction::*field,
                              std::string baseline_model, std::string condition) {
  DiagnosisRole r;
  r.synthetic = {measure.name};
  r.measures = {std::move(measure)};
  r.baseline = std::move(baseline);
  r.baseline_field = field;
  r.baseline_model = std::move(baseline_model);
  r.condition = std::move(condition);
  r.truth_option = "plate_friction";
  return r;
}

Interaction& TiltExperiment::tested_contact(CaseSpec& spec) const { return body_plate_contact(spec); }

std::string TiltExperiment::diagnosis_problem(const CaseSpec& spec) const { return one_body_problem(spec); }

DiagnosticOutcome TiltExperiment::simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>&,
                                                         bool strict) const {
  TiltResult r = run_tilt(spec, {}, strict);
  // The body held on up to max_angle: predict max_angle, the most the rig can tell.
  double angle = r.moved ? r.onset_angle_deg : settings_of<TiltSettings>(spec.experiment).max_angle_deg;
  return {{{role_.measures.front().name, angle}}, {}};
}

const Experiment& slide_experiment() {
  static const TiltExperiment slide(
      "slide", "slide", "slide", "mu_s",
      body_plate_role({"slide_angle", false, "deg"}, {"static_friction", "1", 0.05, 1.2, false},
                      &Interaction::static_friction, "Hertz-Mindlin, Coulomb friction, no cohesion", "material.0.density"));
  return slide;
}

}  // namespace repose
