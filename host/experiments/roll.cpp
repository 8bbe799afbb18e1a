#include "experiments/experiment_simulation.h"
#include "experiments/roll.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "experiments/body_frame.h"
#include "experiments/replicates.h"
#include "experiments/tilt.h"
#include "util/atomic_file.h"
#include "util/progress.h"
#include "util/math.h"

namespace repose {

namespace {

// The incline of the roll rig: beta from the horizontal, falling towards +x.
struct Incline {
  double beta, S;
  Vec3d down, normal;  // along the incline (downhill) and its normal
  explicit Incline(const RollSettings& ex)
      : beta(ex.incline_deg * kPi / 180), S(ex.slope_distance),
        down{std::cos(beta), 0, -std::sin(beta)}, normal{std::sin(beta), 0, std::cos(beta)} {}
};

// Moves the body so that its lowest point (along the incline's normal) rests on the incline with
// its centre S uphill of the foot; returns its extent (largest distance of a surface from the
// centre), which sizes the rig.
double place_on_incline(CaseSpec& spec, const Incline& in) {
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
      h += (s.position[k] - centre[k]) * in.normal[k];
      d2 += (s.position[k] - centre[k]) * (s.position[k] - centre[k]);
    }
    lowest = std::min(lowest, h - s.radius);
    extent = std::max(extent, std::sqrt(d2) + s.radius);
  }
  Vec3d shift;
  for (int k = 0; k < 3; ++k) shift[k] = -centre[k] - in.S * in.down[k] - lowest * in.normal[k];
  shift_to_rest(spec, shift);
  return extent;
}

// The rig's walls, of the plate's material: the incline (a rectangle from the foot up to beyond
// the release point) and the floor.
std::vector<WallSpec> incline_walls(const Incline& in, double extent, int material) {
  double length = in.S + 4 * extent, width = std::max(1.0, 20 * extent);
  WallSpec incline;
  incline.type = WallSpec::Type::Rectangle;
  incline.name = "incline";
  incline.material = material;
  incline.point = {-0.5 * length * in.down[0], 0, -0.5 * length * in.down[2]};
  incline.normal = in.normal;
  incline.edge_axis = in.down;
  incline.size = {length, width};
  WallSpec floor;
  floor.type = WallSpec::Type::Plane;
  floor.name = "floor";
  floor.material = material;
  floor.point = {0, 0, 0};
  floor.normal = {0, 0, 1};
  return {incline, floor};
}

// What the progress line expects: on the incline, how far the body is from the foot (its end
// cannot be told before it meets the floor); on the floor, when its speed, falling linearly under
// the constant rolling torque, reaches stop_speed.
void tell_progress(Progress& progress, FallingTrend& slowing, const RollSample& s, bool on_floor, double stop_speed) {
  if (!on_floor) {
    progress.expect_unknown_end(s.speed < stop_speed ? "(the body has not started rolling)"
                                                     : printf_text("(%.3g m to the foot)", -s.x));
    return;
  }
  slowing.add(s.time, s.speed);
  double stop = slowing.reaches(stop_speed);
  if (stop < 0) progress.expect_unknown_end("(on the floor, not slowing yet)");
  else progress.expect_end_time(stop, "(until the body stops)");
}

// Samples every 5 ms until the body, past the foot (x > 0: the centre is above its contact
// point on the floor), is slower than stop_speed or no longer moves forward (the constant
// rolling torque rocks a stopped body back and forth by a hair). A body that stays slower than
// stop_speed on the incline for kStuckTime after its release does not roll (it rests on its
// ridges): the run ends there rather than at max_time.
constexpr double kStuckTime = 2.0;

void run_until_stopped(const CaseSpec& spec, const ExperimentRunOptions& options, RollResult& r) {
  const RollSettings& ex = settings_of<RollSettings>(spec.experiment);
  const double max_time = spec.experiment.max_time;
  Model model = build_model(spec);
  uint64_t sample_steps = steps_in(0.005, model.dt);
  Simulation sim = experiment_simulation(model, options, sample_steps, 500);
  Progress progress(spec.name + " roll", uint64_t(max_time / model.dt) + 1, model.dt, options.progress);
  FallingTrend slowing(0.5, false);
  bool on_floor = false;
  double previous_x = -1e300, still_since = 0;
  while (true) {
    if (sim.time() >= max_time) {
      r.ending = RollEnding::StillRolling;
      r.problem = spec.path + ": the body had not stopped on the floor after max_time = " + format_number(max_time) +
                  " s (" + (on_floor ? "rolled " + format_number(previous_x) + " m along it" :
                                       "still on the incline at x = " + format_number(previous_x) + " m") + ")";
      r.rolling_distance = std::max(0.0, previous_x);
      r.stop_time = sim.time();
      break;
    }
    sim.advance(sample_steps);
    RollSample s{sim.time(), body_centre(sim.state())[0], body_speed(sim.state())};
    r.trajectory.push_back(s);
    r.wall_forces.sample(sim);
    if (!on_floor && s.x > 0) {
      on_floor = true;
      r.speed_at_foot = s.speed;
    }
    tell_progress(progress, slowing, s, on_floor, ex.stop_speed);
    progress.update(sim.step(), printf_text("x %.4f m, %.3g m/s", s.x, s.speed));
    if (on_floor && (s.speed < ex.stop_speed || s.x <= previous_x)) {
      r.rolling_distance = std::max(s.x, previous_x);
      r.stop_time = sim.time();
      break;
    }
    if (on_floor || s.speed >= ex.stop_speed) still_since = s.time;
    if (s.time - still_since >= kStuckTime) {
      r.ending = RollEnding::DidNotRoll;
      r.problem = spec.path + printf_text(": the body did not roll: it rested on the incline at x = %.4g m, slower than "
                                          "stop_speed = %g m/s for %g s (a clump resting on its ridges, or rolling "
                                          "friction above tan(incline_angle)?)", s.x, ex.stop_speed, kStuckTime);
      r.stop_time = sim.time();
      break;
    }
    previous_x = s.x;
  }
  progress.finish();
}

}  // namespace

namespace {

// Orientations a random_orientation roll draws for one seed before it reports that the body did
// not roll: a lab re-places a cabbage that rests on its ridges.
constexpr int kMostPlacements = 8;

RollResult roll_once(const CaseSpec& input, const ExperimentRunOptions& options, uint64_t orientation_seed) {
  CaseSpec spec = input;
  const RollSettings& ex = settings_of<RollSettings>(spec.experiment);
  if (ex.random_orientation) random_body_orientation(spec, orientation_seed);  // as a replicate does
  int plate_material = spec.walls.at(find_wall(spec, ex.plate, "plate (its material)")).material;
  Incline in(ex);
  double extent = place_on_incline(spec, in);
  spec.walls = incline_walls(in, extent, plate_material);
  RollResult r;
  r.incline_deg = ex.incline_deg;
  r.slope_distance = in.S;
  run_until_stopped(spec, options, r);
  return r;
}

}  // namespace

RollResult run_roll(const CaseSpec& spec, const ExperimentRunOptions& options, bool require_stop) {
  const RollSettings& ex = settings_of<RollSettings>(spec.experiment);
  RollResult r = roll_once(spec, options, spec.seed);
  // Placed anew from a stream of its own (seed + k * 2^32 never meets another replicate's seed).
  for (int k = 1; ex.random_orientation && r.ending == RollEnding::DidNotRoll && k < kMostPlacements; ++k) {
    r = roll_once(spec, options, spec.seed + (uint64_t(k) << 32));
    r.placements = k + 1;
  }
  if (r.ending != RollEnding::Stopped && require_stop) throw std::runtime_error(r.problem);
  Incline in(ex);
  r.mu_r = in.S * std::sin(in.beta) / (in.S * std::cos(in.beta) + r.rolling_distance);
  return r;
}

std::vector<std::string> roll_keys() {
  std::vector<std::string> keys = tilt_keys();
  keys.insert(keys.end(), {"method", "incline_angle", "slope_distance", "stop_speed", "random_orientation"});
  return keys;
}

std::shared_ptr<const ExperimentSettings> read_roll_keys(const Section& s) {
  auto settings = std::make_shared<RollSettings>();
  RollSettings& ex = *settings;
  read_tilt_keys(s, ex);
  ex.method = s.choice<std::string>("method", {{"incline", "incline"}, {"tilt", "tilt"}}, ex.method);
  if (auto b = s.number("incline_angle")) {
    if (!(*b > 0 && *b < 60)) s.fail("incline_angle", format_number(*b) + " must lie between 0 and 60 degrees");
    ex.incline_deg = *b;
  }
  if (auto d = s.number("slope_distance")) ex.slope_distance = positive(s, "slope_distance", *d);
  if (auto v = s.number("stop_speed")) ex.stop_speed = positive(s, "stop_speed", *v);
  ex.random_orientation = s.boolean("random_orientation").value_or(false);
  return settings;
}

// ---------------------------------------------------------------------------------------------
// The registered experiments.

std::vector<std::string> RollExperiment::responses() const {
  return {"rolling_distance", "mu_r", "stop_time", "speed_at_foot"};
}

namespace {

ExperimentOutcome roll_outcome(const CaseSpec& spec, const std::shared_ptr<const RollResult>& r) {
  ExperimentOutcome o;
  bool stopped = r->ending == RollEnding::Stopped;
  if (!stopped) {
    o.status = r->ending == RollEnding::DidNotRoll ? OutcomeStatus::DidNotRoll : OutcomeStatus::StillRolling;
    o.problem = r->problem;
  }
  o.values = {{"rolling_distance", r->rolling_distance}, {"mu_r", r->mu_r}, {"stop_time", r->stop_time},
              {"speed_at_foot", r->speed_at_foot}};
  OrderedJson& j = o.json;
  j["experiment"] = "roll";
  j["method"] = "incline";
  j["case"] = spec.path;
  j["incline_deg"] = r->incline_deg;
  j["slope_distance"] = r->slope_distance;
  j["rolling_distance"] = r->rolling_distance;
  j["mu_r"] = stopped ? OrderedJson(r->mu_r) : OrderedJson(nullptr);  // the formula needs a stop
  j["speed_at_foot"] = r->speed_at_foot;
  j["stop_time"] = r->stop_time;
  j["placements"] = r->placements;
  o.files.push_back(text_file("trajectory.csv", [r](std::ostream& out) {
    out << "t_s,x_m,speed_m_per_s\n";
    for (const auto& s : r->trajectory) out << s.time << "," << s.x << "," << s.speed << "\n";
  }));
  if (!r->wall_forces.rows.empty())
    o.files.push_back(text_file("wall_forces.csv", [r](std::ostream& out) { r->wall_forces.write_csv(out); }));
  if (stopped)
    o.lines.push_back(printf_text(
        "roll %s: beta = %.3g deg, S = %.4g m, rolling distance L = %.4g m, mu_r = S sin(beta) / (S cos(beta) + L) = %.4f",
        spec.name.c_str(), r->incline_deg, r->slope_distance, r->rolling_distance, r->mu_r));
  return o;
}

}  // namespace

ExperimentOutcome RollExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  if (run.replicates > 1) return replicated(spec, run);
  return roll_outcome(spec, std::make_shared<const RollResult>(run_roll(spec, run, run.strict)));
}

// Replicates 1..N: seeds seed ... seed+N-1, the body at a random orientation drawn from each (the
// case's own orientation is not used); the outcome is replicate 1's files and the mean L of the
// replicates that stopped, with every replicate in roll.json. One that does not roll is recorded
// as such and the others go on.
ExperimentOutcome RollExperiment::replicated(const CaseSpec& spec, const ExperimentRun& run) const {
  ExperimentOutcome o;
  OrderedJson list = OrderedJson::array();
  std::vector<double> L;
  for (int k = 0; k < run.replicates; ++k) {
    CaseSpec replicate = spec;
    replicate.seed = spec.seed + uint64_t(k);
    random_body_orientation(replicate, replicate.seed);
    ExperimentRun one = run;
    one.replicates = 1;
    one.frames.name += printf_text("_replicate%d", k + 1);
    auto r = std::make_shared<const RollResult>(run_roll(replicate, one, false));
    if (k == 0) o = roll_outcome(spec, r);
    bool stopped = r->ending == RollEnding::Stopped;
    if (stopped) L.push_back(r->rolling_distance);
    OrderedJson entry = {{"seed", replicate.seed}};
    if (stopped) entry["rolling_distance"] = r->rolling_distance;
    else entry["problem"] = r->problem;
    list.push_back(entry);
    o.lines.push_back(stopped ? printf_text("  replicate %d (seed %llu): L = %.4g m", k + 1, (unsigned long long)replicate.seed,
                                            r->rolling_distance)
                              : printf_text("  replicate %d (seed %llu): %s", k + 1, (unsigned long long)replicate.seed,
                                            r->ending == RollEnding::DidNotRoll ? "did not roll" : "still rolling at max_time"));
  }
  auto [mean, sd] = mean_sd(L);
  const RollSettings& ex = settings_of<RollSettings>(spec.experiment);
  double beta = ex.incline_deg * kPi / 180;
  double mu_r = ex.slope_distance * std::sin(beta) / (ex.slope_distance * std::cos(beta) + mean);
  o.json["replicates"] = {{"runs", list}, {"counted", L.size()}, {"rolling_distance_mean", mean},
                          {"rolling_distance_sd", sd}, {"mu_r_of_mean", L.empty() ? OrderedJson(nullptr) : OrderedJson(mu_r)}};
  if (L.empty()) {
    o.status = OutcomeStatus::DidNotRoll;
    o.problem = spec.path + ": no replicate stopped on the floor (" + std::to_string(run.replicates) + " orientations)";
    if (run.strict) throw std::runtime_error(o.problem);
    return o;
  }
  o.status = OutcomeStatus::Measured;
  o.problem.clear();
  o.values["rolling_distance"] = mean;
  o.values["mu_r"] = mu_r;
  o.lines.push_back(printf_text("  L over %zu of %d replicates: mean %.4g m, sd %.3g m (se %.3g); mu_r of the mean L = %.4f",
                                L.size(), run.replicates, mean, sd, sd / std::sqrt(double(L.size())), mu_r));
  return o;
}

// Rolling friction spans decades between a ball bearing and a cabbage: searched in log.
const DiagnosisRole* RollExperiment::diagnosis() const {
  static const DiagnosisRole role =
      body_plate_role({"roll_distance", false, "m"}, {"rolling_friction", "1", kSmallestRollingFriction, 0.3, true},
                      &Interaction::rolling_friction, "Hertz-Mindlin, constant rolling torque, no air",
                      "experiment.slope_distance");
  return &role;
}

Interaction& RollExperiment::tested_contact(CaseSpec& spec) const { return body_plate_contact(spec); }

std::string RollExperiment::diagnosis_problem(const CaseSpec& spec) const { return one_body_problem(spec); }

DiagnosticOutcome RollExperiment::simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>&,
                                                         bool strict) const {
  // A model far from the data (met while searching) may roll on past max_time: predict the
  // distance reached by then, so the search moves away from it.
  RollResult r = run_roll(spec, {}, strict);
  return {{{"roll_distance", r.rolling_distance}}, {}};
}

// Energy: a body rolling against mu_r m g R stops within S sin(beta) / mu_r; at the smallest
// rolling friction a diagnosis fits that bounds any honest L.
std::string RollExperiment::implausible(const MeasureInfo& m, double value, const CaseSpec& spec) const {
  if (m.name != "roll_distance") return "";
  const RollSettings& ex = settings_of<RollSettings>(spec.experiment);
  double beta = ex.incline_deg * kPi / 180;
  double longest = ex.slope_distance * std::sin(beta) / kSmallestRollingFriction;
  if (!(value > longest)) return "";
  return std::to_string(value) + " m is farther than the body can roll from S = " +
         std::to_string(ex.slope_distance) + " m at rolling friction " +
         std::to_string(kSmallestRollingFriction).substr(0, 5) + " (" + std::to_string(longest) +
         " m): millimetres? Values are in SI units (m)";
}

const Experiment& roll_experiment() {
  static const RollExperiment roll;
  return roll;
}

namespace {

// Roll with method "tilt": a tilting-plate test that reads the roll keys.
class RollTiltExperiment : public TiltExperiment {
 public:
  RollTiltExperiment()
      : TiltExperiment("roll_tilt", "roll", "roll", "mu_r", role()) {}
  std::string description() const override { return "roll, method tilt (mu_r: the tilt at which the body rolls)"; }

 private:
  static DiagnosisRole role() {
    return body_plate_role({"roll_angle", false, "deg"}, {"rolling_friction", "1", kSmallestRollingFriction, 0.3, true},
                           &Interaction::rolling_friction, "Hertz-Mindlin, constant rolling torque, no cohesion",
                           "material.0.density");
  }

 public:
  bool handles(const CaseSpec& spec) const override {
    return settings_of<RollSettings>(spec.experiment).method == "tilt";
  }
  std::vector<std::string> keys() const override { return roll_keys(); }
  std::shared_ptr<const ExperimentSettings> read_keys(const Section& s) const override { return read_roll_keys(s); }
};

}  // namespace

const Experiment& roll_tilt_experiment() {
  static const RollTiltExperiment roll_tilt;
  return roll_tilt;
}

}  // namespace repose
