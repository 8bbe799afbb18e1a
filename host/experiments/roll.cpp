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

// Samples every 5 ms until the body, past the foot (x > 0: the centre is above its contact
// point on the floor), is slower than stop_speed or no longer moves forward (the constant
// rolling torque rocks a stopped body back and forth by a hair).
void run_until_stopped(const CaseSpec& spec, const ExperimentRunOptions& options, bool require_stop, RollResult& r) {
  const RollSettings& ex = settings_of<RollSettings>(spec.experiment);
  Model model = build_model(spec);
  uint64_t sample_steps = steps_in(0.005, model.dt);
  Simulation sim = experiment_simulation(model, options, sample_steps, 500);
  Progress progress(spec.name + " roll", uint64_t(spec.experiment.max_time / model.dt) + 1, model.dt, options.progress);
  bool on_floor = false;
  double previous_x = -1e300;
  while (true) {
    if (sim.time() >= spec.experiment.max_time && !require_stop) {
      r.rolling_distance = std::max(0.0, previous_x);
      r.stop_time = sim.time();
      r.stopped = false;
      break;
    }
    if (sim.time() >= spec.experiment.max_time)
      throw std::runtime_error(spec.path + ": the body had not stopped on the floor after max_time = " +
                               std::to_string(spec.experiment.max_time) + " s");
    sim.advance(sample_steps);
    double x = body_centre(sim.state())[0], speed = body_speed(sim.state());
    r.trajectory.push_back({sim.time(), x, speed});
    r.wall_forces.sample(sim);
    progress.update(sim.step(), "x " + std::to_string(x).substr(0, 6) + " m");
    if (!on_floor && x > 0) {
      on_floor = true;
      r.speed_at_foot = speed;
    }
    if (on_floor && (speed < ex.stop_speed || x <= previous_x)) {
      r.rolling_distance = std::max(x, previous_x);
      r.stop_time = sim.time();
      break;
    }
    previous_x = x;
  }
  progress.finish();
}

}  // namespace

RollResult run_roll(const CaseSpec& input, const ExperimentRunOptions& options, bool require_stop) {
  CaseSpec spec = input;
  const RollSettings& ex = settings_of<RollSettings>(spec.experiment);
  int plate_material = spec.walls.at(find_wall(spec, ex.plate, "plate (its material)")).material;
  Incline in(ex);
  double extent = place_on_incline(spec, in);
  spec.walls = incline_walls(in, extent, plate_material);
  RollResult r;
  r.incline_deg = ex.incline_deg;
  r.slope_distance = in.S;
  run_until_stopped(spec, options, require_stop, r);
  r.mu_r = in.S * std::sin(in.beta) / (in.S * std::cos(in.beta) + r.rolling_distance);
  return r;
}

std::vector<std::string> roll_keys() {
  std::vector<std::string> keys = tilt_keys();
  keys.insert(keys.end(), {"method", "incline_angle", "slope_distance", "stop_speed"});
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
  return settings;
}

// ---------------------------------------------------------------------------------------------
// The registered experiments.

std::vector<std::string> RollExperiment::responses() const {
  return {"rolling_distance", "mu_r", "stop_time", "speed_at_foot"};
}

ExperimentOutcome RollExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  auto r = std::make_shared<RollResult>(run_roll(spec, run, run.strict));
  ExperimentOutcome o;
  if (!r->stopped) {
    o.status = OutcomeStatus::StillRolling;
    o.problem = spec.path + ": the body had not stopped on the floor after max_time = " +
                std::to_string(spec.experiment.max_time) + " s";
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
  j["mu_r"] = r->mu_r;
  j["speed_at_foot"] = r->speed_at_foot;
  j["stop_time"] = r->stop_time;
  o.files.push_back(text_file("trajectory.csv", [r](std::ostream& out) {
    out << "t,x,speed\n";
    for (const auto& s : r->trajectory) out << s.time << "," << s.x << "," << s.speed << "\n";
  }));
  if (!r->wall_forces.rows.empty())
    o.files.push_back(text_file("wall_forces.csv", [r](std::ostream& out) { r->wall_forces.write_csv(out); }));
  o.lines.push_back(printf_text(
      "roll %s: beta = %.3g deg, S = %.4g m, rolling distance L = %.4g m, mu_r = S sin(beta) / (S cos(beta) + L) = %.4f",
      spec.name.c_str(), r->incline_deg, r->slope_distance, r->rolling_distance, r->mu_r));
  o.written = [](const std::string& dir) { return "wrote " + dir + "/roll.json, trajectory.csv, wall_forces.csv"; };
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
