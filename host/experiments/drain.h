// The angle of repose by draining (the drained or emptying angle), the second bulk test of
// agricultural studies beside the poured heap: the particles settle in a box whose floor has an
// opening beside one wall, closed by a gate; the gate opens (its [[wall]] motion), what lies above
// the opening flows out, and what stays behind settles into a slope falling towards the opening.
// Its angle is measured from the front view as the heap tests measure theirs (host/measure), on
// the side that faces the opening. Grains that interlock, roll badly or cohere stand steeper.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "experiments/experiment.h"
#include "experiments/run_options.h"
#include "geometry/sphere.h"
#include "measure/heap_angle.h"

namespace repose {

// The drain's [experiment] keys.
struct DrainSettings : ExperimentSettings {
  std::string gate;               // the [[wall]] that closes the opening: its motion opens it
  std::optional<double> floor_z;  // the opening's level (m): below it a particle has drained out;
                                  // default the gate's centre (its point)
  double settle_energy = 1e-4;    // J: settled when no particle left in the box has more
  std::string view = "y";         // the camera looks along +y ("y") or +x ("x")
};

struct DrainResult {
  double angle_deg = 0;           // the slope that faces the opening
  bool sloped = true;             // false: no measurable slope (require_slope off; angle 0)
  std::string problem;            // then: why, in words
  HeapAngle heap;                 // the front-view measurement of what stayed
  std::string side;               // the picture's slope that faces the opening: "left" or "right"
  double floor_z = 0;             // m
  double drained_fraction = 0;    // of the particles (by count), below the floor when settled
  size_t particles_left = 0;      // in the box, measured
  double settle_time = 0;         // s
  std::vector<Sphere> spheres;    // those left in the box
  std::vector<std::pair<double, double>> energy;  // (t, largest kinetic energy in the box)
};

// Fills and settles the case's particles, opens the gate at its motion's start, runs until no
// particle left in the box has more than settle_energy (sampled every 0.05 s, at two samples
// running) and measures the slope. Throws std::runtime_error naming the case when the box has not
// settled by max_time, or (require_slope) when no slope faces the opening.
DrainResult run_drain(const CaseSpec& spec, const ExperimentRunOptions& options = {}, bool require_slope = true);

// The drain as a registered experiment: keys gate, floor_z, settle_energy and view; `repose
// experiment drain` writes drain.json, heap.png and heap.csv.
class DrainExperiment : public Experiment {
 public:
  std::string id() const override { return "drain"; }
  std::string description() const override { return "drain (angle of repose by draining through an opening)"; }
  std::vector<std::string> keys() const override { return {"gate", "floor_z", "settle_energy", "view"}; }
  std::vector<std::string> wall_keys() const override { return {"gate"}; }
  std::shared_ptr<const ExperimentSettings> read_keys(const Section& s) const override;
  std::vector<std::string> responses() const override;
  ExperimentOutcome run(const CaseSpec& spec, const ExperimentRun& run) const override;
};

const Experiment& drain_experiment();

}  // namespace repose
