// The inclined rolling test of the cabbage study: the body is released at rest on a plate inclined
// at beta, its contact point a slope distance S above the foot, rolls down and onto a horizontal
// plate, and stops after a distance L there; mu_r = S sin(beta) / (S cos(beta) + L) (the study's Eq. 4).
#pragma once
#include <vector>

#include "case/case_spec.h"
#include "experiments/experiment.h"
#include "experiments/tilt.h"
#include "experiments/run_options.h"
#include "experiments/wall_force_series.h"

namespace repose {

struct RollSample {
  double time = 0;
  double x = 0;      // body centre along the rolling direction, from the foot of the incline, m
  double speed = 0;  // m/s
};

// How a roll ended: the body stopped on the floor (L measured), was still rolling at max_time,
// or never rolled down the incline (it rests on it).
enum class RollEnding { Stopped, StillRolling, DidNotRoll };

struct RollResult {
  double incline_deg = 0, slope_distance = 0;
  double rolling_distance = 0;  // L, m, from the foot of the incline to where the body stopped
  double mu_r = 0;              // the study's formula
  double stop_time = 0;
  double speed_at_foot = 0;     // m/s when the centre passed the foot
  int placements = 1;           // random_orientation: orientations drawn until one rolled
  RollEnding ending = RollEnding::Stopped;  // anything else only when a stop is not required
  std::string problem;          // not Stopped: what happened, in words
  std::vector<RollSample> trajectory;
  WallForceSeries wall_forces;
};

// The case's particles are the body and its first [[wall]] gives the plates' material; the rig
// (an incline rectangle and a floor plane meeting at x = 0, rolling towards +x, z up) replaces
// the case's walls. Throws std::runtime_error naming the case when the body does not stop on
// the floor by max_time or never rolls, unless `require_stop` is false: then L is where it got
// to by then (0 on the incline) and `ending` says why.
RollResult run_roll(const CaseSpec& spec, const ExperimentRunOptions& options = {}, bool require_stop = true);

// The [experiment] keys of a roll case: both methods, so the tilt's and the incline's.
struct RollSettings : TiltSettings {
  std::string method = "incline";  // "incline" (release, roll onto the floor) or "tilt"
  double incline_deg = 10;         // beta
  double slope_distance = 0.26;    // S, m along the incline from the release point to the foot
  double stop_speed = 0.005;       // m/s: the body has stopped
  bool random_orientation = false; // the body at an orientation drawn from simulation.seed (a seed is a
                                   // replicate); one that rests on its ridges is placed anew, as in the lab
};

// The smallest rolling friction a diagnosis tries (a ball bearing): also what bounds a believable
// rolling distance in measured data.
constexpr double kSmallestRollingFriction = 0.002;

// The [experiment] keys of a roll case (both methods: the tilt keys, method and the incline's),
// and their reader.
std::vector<std::string> roll_keys();
std::shared_ptr<const ExperimentSettings> read_roll_keys(const Section& s);

// The incline roll as a registered experiment: `repose experiment roll` writes roll.json,
// trajectory.csv and wall_forces.csv; a diagnosis fits the body-plate rolling friction to L.
class RollExperiment : public Experiment {
 public:
  std::string id() const override { return "roll"; }
  std::string description() const override { return "roll (rolling friction: incline + floor)"; }
  bool handles(const CaseSpec& spec) const override {
    return settings_of<RollSettings>(spec.experiment).method != "tilt";
  }
  std::vector<std::string> keys() const override { return roll_keys(); }
  std::vector<std::string> wall_keys() const override { return {"plate"}; }
  std::shared_ptr<const ExperimentSettings> read_keys(const Section& s) const override { return read_roll_keys(s); }
  std::vector<std::string> responses() const override;
  ExperimentOutcome run(const CaseSpec& spec, const ExperimentRun& run) const override;
  bool takes_replicates() const override { return true; }
  const DiagnosisRole* diagnosis() const override;
  Interaction& tested_contact(CaseSpec& spec) const override;
  std::string diagnosis_problem(const CaseSpec& spec) const override;
  DiagnosticOutcome simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>& wanted,
                                           bool strict) const override;
  std::string implausible(const MeasureInfo& m, double value, const CaseSpec& spec) const override;

 private:
  ExperimentOutcome replicated(const CaseSpec& spec, const ExperimentRun& run) const;
};

const Experiment& roll_experiment();
// Roll with method "tilt": the tilt at which a body starts to roll (a tilting-plate test).
const Experiment& roll_tilt_experiment();

}  // namespace repose
