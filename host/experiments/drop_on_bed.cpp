#include "experiments/drop_on_bed.h"

#include <algorithm>
#include <stdexcept>

#include "case/body_pose.h"
#include "experiments/body_frame.h"
#include "util/math.h"

namespace repose {

namespace {

bool has_bed(const CaseSpec& spec) {
  return std::any_of(spec.spheres.begin(), spec.spheres.end(), [](const SphereSpec& s) { return s.fixed; }) ||
         std::any_of(spec.bodies.begin(), spec.bodies.end(), [](const BodySpec& b) { return b.fixed; });
}

// The spheres of the case as placed, the bed's (fixed) or the body's (moving).
std::vector<SphereSpec> spheres_of(const CaseSpec& spec, bool fixed) {
  std::vector<SphereSpec> out;
  for (const SphereSpec& s : spec.spheres)
    if (s.fixed == fixed) out.push_back(s);
  for (const BodySpec& b : spec.bodies)
    if (b.fixed == fixed)
      for (SphereSpec s : body_spheres(b, spec.templates[size_t(b.template_index)])) {
        s.material = b.material;
        out.push_back(s);
      }
  return out;
}

// Up is against gravity; the level is the bed's highest point.
DropSurface bed_top(const CaseSpec& spec) {
  double g = length(spec.gravity);
  if (!(g > 0)) throw std::runtime_error(spec.path + ": a drop onto a bed needs gravity");
  DropSurface bed;
  bed.up = mul(spec.gravity, -1.0 / g);
  bed.level = -1e300;
  for (const SphereSpec& s : spheres_of(spec, true)) bed.level = std::max(bed.level, dot(s.position, bed.up) + s.radius);
  return bed;
}

size_t moving_spheres(const CaseSpec& spec) {
  return size_t(std::count_if(spec.spheres.begin(), spec.spheres.end(), [](const SphereSpec& s) { return !s.fixed; }));
}
size_t moving_bodies(const CaseSpec& spec) {
  return size_t(std::count_if(spec.bodies.begin(), spec.bodies.end(), [](const BodySpec& b) { return !b.fixed; }));
}

class DropOnBedExperiment : public DropExperiment {
 public:
  std::string id() const override { return "drop_on_bed"; }
  std::string type() const override { return "drop"; }
  std::string description() const override { return "drop onto a bed of fixed bodies (restitution between the two)"; }
  bool handles(const CaseSpec& spec) const override { return has_bed(spec); }

  const DiagnosisRole* diagnosis() const override {
    static const DiagnosisRole role = [] {
      DiagnosisRole r = *drop_experiment().diagnosis();
      r.baseline_model = "Hertz-Mindlin, constant restitution between the body and the bed";
      return r;
    }();
    return &role;
  }

  // The body's material with the bed's (its first fixed particle's).
  Interaction& tested_contact(CaseSpec& spec) const override {
    std::vector<SphereSpec> body = spheres_of(spec, false), bed = spheres_of(spec, true);
    if (body.empty() || bed.empty()) throw std::runtime_error(spec.path + ": a drop onto a bed needs a body and a bed");
    return interaction_between(spec, body.front().material, bed.front().material, "the body and the bed");
  }

  std::string diagnosis_problem(const CaseSpec& spec) const override {
    if (moving_spheres(spec) == 1 && moving_bodies(spec) == 0) return "";
    return "diagnose drops one sphere onto the bed (a clump body is what the `shape` extension tests)";
  }

  bool stochastic(const CaseSpec& spec) const override { return moving_bodies(spec) > 0; }

 protected:
  DropResult drop(const CaseSpec& spec, const DropOptions& options) const override {
    if (moving_spheres(spec) + moving_bodies(spec) != 1)
      throw std::runtime_error(spec.path + ": a drop onto a bed needs exactly one body that is not fixed (a [[sphere]] "
                               "or a [[clump]]); the case has " + std::to_string(moving_spheres(spec)) +
                               " spheres and " + std::to_string(moving_bodies(spec)) + " clumps that move");
    return drop_onto(spec, bed_top(spec), options);
  }
};

}  // namespace

const Experiment& drop_on_bed_experiment() {
  static const DropOnBedExperiment experiment;
  return experiment;
}

}  // namespace repose
