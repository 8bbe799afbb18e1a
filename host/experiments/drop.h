// The free-fall collision test of both studies: a body released at rest with its lowest point H
// above a plate; a simulated high-speed camera tracks the lowest point, the rebound height h is
// the highest point seen after the first impact, and e = sqrt(h/H) (the cabbage study's Eq. 1).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "case/case_spec.h"
#include "engine/step_program.h"
#include "experiments/wall_force_series.h"
#include "experiments/experiment.h"
#include "experiments/run_options.h"

namespace repose {

// The drop's [experiment] keys.
struct DropSettings : ExperimentSettings {
  double drop_height = 0.5;  // m: the body's lowest point above the plate at release
  double camera_fps = 1000;  // frames per second of the simulated high-speed camera
};

// How a drop runs: the run options of every experiment and the drop's own.
struct DropOptions : ExperimentRunOptions {
  bool random_orientation = true;  // a clump falls at a random orientation drawn from the seed
  bool require_rebound = true;     // false: a body that never leaves the plate is a result
  std::string label = "drop";      // the progress line's ("drop, replicate 2 of 3")
};
DropOptions drop_options(const ExperimentRunOptions& run, bool require_rebound);

struct DropResult {
  double drop_height = 0;           // H, m
  double rebound_height = 0;        // h seen by the camera (parabola through the top frames), m
  double rebound_height_exact = 0;  // apex of the free flight after lift-off, m
  double restitution = 0;           // sqrt(h/H)
  double impact_speed = 0;          // m/s, normal to the plate, just before contact
  double contact_time = 0;          // s, first impact
  bool rebounded = true;            // false: still on the plate at max_time (require_rebound off)
  // Another reading of the rebound: how far the centre of mass rises from its lowest point
  // (deepest in the plate) to its apex after the first impact. For a sphere that is h plus the
  // largest overlap: a soft body sinks into the plate ~1/10 of its rebound.
  double centre_rise = 0;           // m
  int peak_touching = 0;            // most spheres of the body in the plate at one frame (first impact)
  std::vector<std::pair<double, double>> trajectory;  // (t, height of the lowest point)
  std::vector<double> centre_trajectory;              // height of the centre of mass, same frames
  WallForceSeries wall_forces;                         // the plate's force at every camera frame
};

// Where a drop is measured from: `up` (unit, against gravity) and the level along it from which
// the release height and the camera's heights count (the plate; a bed's top).
struct DropSurface {
  Vec3d up{0, 0, 1};
  double level = 0;
};

// Releases the case's body (its one sphere, else its one clump) at rest with its lowest point
// drop_height above the surface and films its fall and rebound as run_drop does; particles that
// do not move (fixed: the rig's) are not filmed. Throws std::runtime_error naming the case
// without gravity towards the surface or (require_rebound) when the body never rebounds.
DropResult drop_onto(const CaseSpec& spec, const DropSurface& surface, const DropOptions& options = {});

// The case's one sphere or one clump is the body (a clump at a random orientation from
// simulation.seed unless options say otherwise), its first plane wall the plate; [experiment]
// drop_height, camera_fps and max_time apply. Throws std::runtime_error naming the case when
// the case is not a drop test or (require_rebound) the body never rebounds.
DropResult run_drop(const CaseSpec& spec, const DropOptions& options = {});

// Shifts the case's time step so that the body meets the plate half a step after a step boundary
// (its fall from rest, with air drag on a sphere, computed in closed form). A drop's rebound then
// varies smoothly with the parameters instead of jumping where the impact crosses a step: the
// diagnosis's fits need that (docs/diagnosis.md).
void align_impact_phase(CaseSpec& spec);

// The drop as a registered experiment (experiments/registry.h): keys drop_height and camera_fps;
// `repose experiment drop` writes drop.json and trajectory.csv; a diagnosis fits the body-plate
// restitution to rebound heights, restitutions and the camera's track.
class DropExperiment : public Experiment {
 public:
  std::string id() const override { return "drop"; }
  std::string description() const override { return "drop (restitution)"; }
  std::vector<std::string> keys() const override { return {"drop_height", "camera_fps"}; }
  std::shared_ptr<const ExperimentSettings> read_keys(const Section& s) const override;
  std::vector<std::string> responses() const override;
  ExperimentOutcome run(const CaseSpec& spec, const ExperimentRun& run) const override;
  const DiagnosisRole* diagnosis() const override;
  Interaction& tested_contact(CaseSpec& spec) const override;
  std::string diagnosis_problem(const CaseSpec& spec) const override;
  bool stochastic(const CaseSpec& spec) const override { return !spec.bodies.empty(); }
  bool takes_replicates() const override { return true; }
  DiagnosticOutcome simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>& wanted,
                                           bool strict) const override;
  std::string implausible(const MeasureInfo& m, double value, const CaseSpec& spec) const override;

 protected:
  // The outcome of one measured drop (values, JSON, camera track) and of its replicates.
  ExperimentOutcome outcome(const CaseSpec& spec, const DropResult& r) const;
  void add_replicates(ExperimentOutcome& o, const CaseSpec& spec, const ExperimentRun& run, const DropResult& first) const;
  virtual DropResult drop(const CaseSpec& spec, const DropOptions& options) const { return run_drop(spec, options); }
};

const Experiment& drop_experiment();

}  // namespace repose
