// Angle-of-repose rigs of the studies: the particles settle in a container, one wall of it lifts
// or is pulled (drawing-plate baffle, bottomless cylinder, bucket gate: the case's [[wall]]
// motion), the heap settles, and its angle is measured from a front-view picture as the
// studies did (host/measure): both slopes, their mean, and for axisymmetric heaps a 3D sector fit.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "engine/run_profile.h"
#include "experiments/experiment.h"
#include "experiments/run_options.h"
#include "experiments/wall_force_series.h"
#include "measure/heap_angle.h"
#include "measure/heap_profile.h"
#include "measure/heap_views.h"

namespace repose {

// The [experiment] keys of a repose rig.
struct ReposeSettings : ExperimentSettings {
  std::string lift_wall;           // the wall that lifts or is pulled (its [[wall]] motion)
  double lift_end = 0;             // s: the lift is over (default: the wall's motion stop)
  bool end_when_clear = true;      // the lift is also over once the lifted wall has touched no
                                   // particle for two samples: the rest of its motion cannot
                                   // change the heap (repose.cpp)
  double settle_energy = 1e-4;     // J: settled when no particle (or body) has more
  std::string view = "y";          // camera looks along +y ("y") or +x ("x")
  std::string heap_side = "both";  // which slope is the angle: "left", "right", "both" (mean)
  bool axisymmetric = false;       // also the 3D sector fit (bottomless cylinder)
  int views = 1;                   // > 1: the angle is the mean slope of that many front views
                                   // over half a turn about the heap axis (needs heap_side both)
  std::optional<double> heap_floor_z;  // default: the lowest sphere bottom
  std::optional<double> visible_from;  // m along the picture: what lies before it is hidden
                                       // (an opaque box's front wall; HeapAngleOptions)
};

struct ReposeResult {
  double angle_deg = 0;           // per [experiment] heap_side: left, right or their mean
  HeapAngle heap;                 // the 2D measurement (with its picture)
  HeapProfile profile;            // the same picture's height, run-out and convexity per side
  std::optional<HeapViewsAngle> views;  // [experiment] views > 1: then angle_deg is their mean
  std::optional<AxisymmetricHeapAngle> heap_3d;
  double settle_time = 0;         // s when the heap was judged settled
  // The bed before the lift (first sample at or after the lift wall's motion start): twice the
  // volume-weighted mean height of the particles above the floor, the height a uniform bed of
  // the same particles would have. At a given count it falls as the bed packs denser.
  double bed_height = 0;          // m
  double kinetic_energy = 0;      // J, the largest of any particle (or body) then
  bool settled = true;            // false: measured at max_time while something still moved
                                  // (only when the caller allows it, see run_repose)
  bool sloped = true;             // false: no measurable slope (require_slope off; angle 0)
  std::string problem;            // then: why, in words
  size_t particles_measured = 0;  // above the heap floor, resting on it
  size_t particles_apart = 0;     // above the floor, apart from the heap (on a hopper, a gate)
  std::vector<std::pair<double, double>> energy;  // (t, largest kinetic energy of a particle)
  std::vector<Sphere> spheres;    // the settled heap
  WallForceSeries wall_forces;
  // Where the time went: "fill" (before the lift starts: pouring and settling), "lift", "run-out"
  // (after the lift until settled); wall time includes the experiment's own sampling.
  std::vector<std::pair<std::string, RunProfile>> phases;
  // The checkpoints this process wrote and their wall time (outside the phases' times; not kept
  // in a checkpoint, so a restarted run counts its own).
  uint64_t checkpoints_written = 0;
  double checkpoint_seconds = 0;
  double dt = 0;  // s, the time step
};

// Runs until the lift is over (lift_end, default the lift wall's motion stop, or with
// end_when_clear once the lifted wall has touched nothing at two samples) and the kinetic
// energy of every particle (or body) is below settle_energy, then measures. Throws std::runtime_error naming
// the case when the heap has not settled by max_time (unless `measure_unsettled`: then it measures
// the heap as it stands at max_time, settled = false; the diagnosis does, since a lone grain that
// keeps spinning on the floor, as one can under rolling = "epsd", which has no twisting
// resistance, leaves the heap's shape as it is) or the measurement finds no slope.
// `require_slope` false: a heap without a measurable slope is a result (sloped false), not an error.
ReposeResult run_repose(const CaseSpec& spec, const ExperimentRunOptions& options = {},
                        bool measure_unsettled = false, bool require_slope = true);

// The bed alone, run up to the lift (a third of a heap's cost): run_repose's bed_height.
double measure_bed_height(const CaseSpec& spec);

// What a diagnosed heap reports, by measure name: the angle and the bed height, and the shape of
// the heap in the same picture (measure/heap_profile.h): its height, its run-out and its profile's
// convexity, taken on heap_side (the two sides' mean for "both"). In the order data files list
// them: repose_angle, bed_height, heap_height, runout, profile_convexity.
const std::vector<std::string>& heap_measure_names();
std::map<std::string, double> heap_measures(const ReposeResult& heap, const std::string& heap_side);
// The same from a measured picture (repose heap-angle on a user's own heap): the angle of the side
// asked for, the bed height of a bed before the lift. A side whose profile could not be measured
// gives a convexity of 0, as a flat heap would; its run-out is still measured.
std::map<std::string, double> heap_measures(double angle_deg, double bed_height, const HeapProfile& profile,
                                            const std::string& heap_side);

// The [experiment] keys of a repose rig, and their reader.
std::vector<std::string> repose_keys();
std::shared_ptr<const ExperimentSettings> read_repose_keys(const Section& s);

// The angle of repose as a registered experiment: `repose experiment repose` writes repose.json,
// heap.png, heap.csv, energy.csv and wall_forces.csv; a diagnosis fits the grains' sliding
// friction to angles and bed heights of heaps filled from sphere [[fill]]s.
class ReposeExperiment : public Experiment {
 public:
  std::string id() const override { return "repose"; }
  std::string description() const override { return "repose (angle of repose of a rig)"; }
  std::vector<std::string> keys() const override { return repose_keys(); }
  std::vector<std::string> wall_keys() const override { return {"lift_wall"}; }
  std::shared_ptr<const ExperimentSettings> read_keys(const Section& s) const override { return read_repose_keys(s); }
  std::vector<std::string> responses() const override;
  ExperimentOutcome run(const CaseSpec& spec, const ExperimentRun& run) const override;
  void check_case(const CaseSpec& spec) const override;
  const DiagnosisRole* diagnosis() const override;
  Interaction& tested_contact(CaseSpec& spec) const override;
  std::string diagnosis_problem(const CaseSpec& spec) const override;
  void prepare_for_diagnosis(CaseSpec& spec) const override { spec.spheres.clear(); }
  void replicate(CaseSpec& spec, int r) const override;
  void reseed(CaseSpec& spec, uint64_t seed) const override;
  bool stochastic(const CaseSpec&) const override { return true; }
  bool resumable() const override { return true; }
  DiagnosticOutcome simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>& wanted,
                                           bool strict) const override;
  std::string implausible(const MeasureInfo& m, double value, const CaseSpec& spec) const override;
};

const Experiment& repose_experiment();

}  // namespace repose
