// The tilting-plate tests of both studies: a body rests on a plate that tilts slowly at a constant
// rate from level; the tilt at which the body starts to move down the plate gives
// mu = tan(alpha): sliding for a body that cannot roll (the cabbage study's four bonded
// cabbages: static friction), rolling for a single stalk (the cotton-stalk study: rolling friction
// angle).
#pragma once
#include <vector>

#include "case/case_spec.h"
#include "experiments/experiment.h"
#include "experiments/run_options.h"
#include "experiments/wall_force_series.h"

namespace repose {

struct TiltSample {
  double time = 0, angle_deg = 0;
  double displacement = 0;  // body centre along the plate, relative to it, since the tilt began, m
};

struct TiltResult {
  double onset_angle_deg = 0;  // alpha
  double tan_alpha = 0;        // mu_s (slide) or the rolling friction coefficient (tilt roll)
  double onset_time = 0;       // s
  double rolled_fraction = 0;  // first body's rotation x rolling radius / displacement: ~1 rolls, ~0 slides
  bool moved = true;           // false: held on up to max_angle or max_time (require_motion off)
  std::vector<TiltSample> trajectory;
  WallForceSeries wall_forces;
};

// The [experiment] keys of a tilting plate (slide; roll with method "tilt" adds its own).
struct TiltSettings : ExperimentSettings {
  std::string plate;            // wall name; default the first wall
  double tilt_rate_deg = 1.0;   // deg/s about `tilt_axis` through the plate's centre
  Vec3d tilt_axis{0, 1, 0};
  double settle_time = 0.5;     // s at rest before the tilt starts
  double onset_distance = 1e-3; // m the body moves relative to the plate: it slides (or rolls)
  double onset_speed = 0;       // m/s > 0: the onset is where its speed relative to the plate first
                                // reaches this instead (a soft body creeps its first mm early)
  double max_angle_deg = 60;    // give up beyond this tilt
};

// The plate is [experiment] plate (default the first wall: a rectangle or a plane); its motion is
// replaced by the tilt: about tilt_axis through its centre at tilt_rate deg/s after settle_time.
// Onset: the body centre moved onset_distance relative to the plate. Throws std::runtime_error
// naming the case when the body never moves up to max_angle, or at max_time (unless
// `require_motion` is false: then moved is false).
// expected_onset_deg (> 0): where the progress line expects the onset (atan of the coefficient).
TiltResult run_tilt(const CaseSpec& spec, const ExperimentRunOptions& options = {}, bool require_motion = true,
                    double expected_onset_deg = -1);

// The [experiment] keys of a tilting plate, and their reader.
std::vector<std::string> tilt_keys();
void read_tilt_keys(const Section& s, TiltSettings& ex);

// A tilting-plate test as a registered experiment: `repose experiment` writes TYPE.json,
// trajectory.csv and wall_forces.csv; its outcome is the onset angle, tan(alpha) and how much
// the body rolled; a diagnosis fits the body-plate friction the test measures to the onset angle.
class TiltExperiment : public Experiment {
 public:
  // motion: what the body starts to do ("slide", "roll"); quantity: what tan(alpha) is ("mu_s").
  TiltExperiment(std::string id, std::string type, std::string motion, std::string quantity, DiagnosisRole role)
      : id_(std::move(id)), type_(std::move(type)), motion_(std::move(motion)), quantity_(std::move(quantity)),
        role_(std::move(role)) {}
  std::string id() const override { return id_; }
  std::string type() const override { return type_; }
  std::string description() const override { return type_ + " (" + quantity_ + " on a tilting plate)"; }
  std::vector<std::string> keys() const override { return tilt_keys(); }
  std::vector<std::string> wall_keys() const override { return {"plate"}; }
  std::shared_ptr<const ExperimentSettings> read_keys(const Section& s) const override;
  std::vector<std::string> responses() const override;
  ExperimentOutcome run(const CaseSpec& spec, const ExperimentRun& run) const override;
  const DiagnosisRole* diagnosis() const override { return &role_; }
  Interaction& tested_contact(CaseSpec& spec) const override;
  std::string diagnosis_problem(const CaseSpec& spec) const override;
  DiagnosticOutcome simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>& wanted,
                                           bool strict) const override;

 private:
  double expected_onset_deg(const CaseSpec& spec) const;
  std::string id_, type_, motion_, quantity_;
  DiagnosisRole role_;
};

// The contact between a tilt or roll case's body (its first sphere, else its first clump) and its
// plate ([experiment] plate, default the first wall); throws naming the case when absent.
Interaction& body_plate_contact(CaseSpec& spec);
// Why a diagnosis cannot tilt or roll this case's body ("" when it can: one sphere or one clump).
std::string one_body_problem(const CaseSpec& spec);
// The diagnosis role of a one-body test on a plate: one scalar measure, the baseline a friction
// of the body-plate contact (synth-data's --plate-friction sets the truth's).
DiagnosisRole body_plate_role(MeasureInfo measure, FreeParameter baseline, double Interaction::*field,
                              std::string baseline_model, std::string condition);

const Experiment& slide_experiment();

}  // namespace repose
