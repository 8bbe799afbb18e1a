#include "experiments/drain.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "engine/kinetic_energy.h"
#include "engine/model.h"
#include "experiments/body_frame.h"
#include "experiments/experiment_simulation.h"
#include "measure/heap_json.h"
#include "measure/heap_png.h"
#include "util/progress.h"

namespace repose {

namespace {

// Whether a particle is still in the box: its bottom not below the opening's level by more than
// half its radius (one that sits in the opening still belongs to the slope).
bool in_box(const gpu::vec4& p, double floor_z) { return double(p.z) - p.w >= floor_z - 0.5 * p.w; }

// Runs, sampled every 0.05 s, until the gate has opened and no particle in the box has had more
// than settle_energy at two samples running; the energies go into r.
void run_until_drained(const CaseSpec& spec, const ExperimentRunOptions& options, const WallSpec& gate,
                       Simulation& sim, DrainResult& r) {
  const DrainSettings& ex = settings_of<DrainSettings>(spec.experiment);
  double dt = sim.model().dt;
  uint64_t sample_steps = steps_in(0.05, dt);
  Progress progress(spec.name + " drain", uint64_t(spec.experiment.max_time / dt) + 1, dt, options.progress);
  bool calm_before = false;
  while (true) {
    sim.advance(sample_steps);
    // The particles still in the box: those that drained keep falling or bouncing below it.
    double e = largest_kinetic_energy(sim, [&](const gpu::vec4& centre) { return in_box(centre, r.floor_z); });
    r.energy.push_back({sim.time(), e});
    progress.update(sim.step(), "max E " + std::to_string(e).substr(0, 8) + " J");
    bool calm = sim.time() > gate.motion.start_time && e < ex.settle_energy;
    if (calm && calm_before) break;
    calm_before = calm;
    if (sim.time() >= spec.experiment.max_time)
      throw std::runtime_error(spec.path + ": the box had not settled after draining (largest kinetic energy " +
                               std::to_string(e) + " J of a particle in it, settle_energy " +
                               std::to_string(ex.settle_energy) + ") by max_time = " +
                               std::to_string(spec.experiment.max_time) + " s");
  }
  r.settle_time = sim.time();
  progress.finish();
}

// The front-view measurement of what stayed in the box, on the side that faces the opening.
void measure_drained(const CaseSpec& spec, const WallSpec& gate, const HostState& state, bool require_slope,
                     DrainResult& r) {
  const DrainSettings& ex = settings_of<DrainSettings>(spec.experiment);
  for (const auto& p : state.pos)
    if (in_box(p, r.floor_z)) r.spheres.push_back({{p.x, p.y, p.z}, p.w});
  r.particles_left = r.spheres.size();
  r.drained_fraction = 1.0 - double(r.particles_left) / double(state.pos.size());
  if (r.spheres.empty()) throw std::runtime_error(spec.path + ": the box drained completely: no slope stayed");
  HeapAngleOptions opts;
  opts.view = ex.view == "x" ? ViewAxis::X : ViewAxis::Y;
  opts.floor_z = r.floor_z;
  r.heap = measure_heap_angle(r.spheres, opts);
  double opening = ex.view == "x" ? gate.point[1] : gate.point[0];  // the picture's horizontal axis
  r.side = opening > r.heap.crest ? "right" : "left";
  const SlopeFit& side = r.side == "right" ? r.heap.right : r.heap.left;
  if (side.valid) {
    r.angle_deg = side.angle_deg;
    return;
  }
  std::string problem = "no slope faces the opening: " + side.problem;
  if (require_slope) throw std::runtime_error(spec.path + ": " + problem);
  r.sloped = false;
  r.problem = spec.path + ": " + problem;
}

}  // namespace

DrainResult run_drain(const CaseSpec& spec, const ExperimentRunOptions& options, bool require_slope) {
  const DrainSettings& ex = settings_of<DrainSettings>(spec.experiment);
  const WallSpec& gate = spec.walls.at(find_wall(spec, ex.gate, "gate over the opening"));
  const WallMotion& m = gate.motion;
  bool moves = m.velocity[0] != 0 || m.velocity[1] != 0 || m.velocity[2] != 0 || m.angular_rate != 0;
  if (!moves || !(m.start_time < spec.experiment.max_time))
    throw std::runtime_error(spec.path + ": the gate '" + gate.name + "' must move (its motion opens the opening) "
                             "before max_time = " + std::to_string(spec.experiment.max_time) + " s");
  Model model = build_model(spec);
  Simulation sim = experiment_simulation(model, options, steps_in(0.05, model.dt), 200);
  DrainResult r;
  r.floor_z = ex.floor_z.value_or(gate.point[2]);
  run_until_drained(spec, options, gate, sim, r);
  measure_drained(spec, gate, sim.state(), require_slope, r);
  return r;
}

// ---------------------------------------------------------------------------------------------
// The registered experiment.

std::shared_ptr<const ExperimentSettings> DrainExperiment::read_keys(const Section& s) const {
  auto settings = std::make_shared<DrainSettings>();
  DrainSettings& ex = *settings;
  ex.gate = s.text("gate").value_or("");
  if (ex.gate.empty()) s.missing("gate", " (the name of the [[wall]] that closes the opening; its motion opens it)");
  if (auto z = s.number("floor_z")) ex.floor_z = *z;
  if (auto e = s.number("settle_energy")) ex.settle_energy = positive(s, "settle_energy", *e);
  ex.view = s.choice<std::string>("view", {{"x", "x"}, {"y", "y"}}, ex.view);
  return settings;
}

std::vector<std::string> DrainExperiment::responses() const {
  return {"drained_angle", "drained_fraction", "settle_time", "particles_left"};
}

ExperimentOutcome DrainExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  auto r = std::make_shared<const DrainResult>(run_drain(spec, run, run.strict));
  ExperimentOutcome o;
  if (!r->sloped) {  // what stayed in the box is still written, with the reason
    o.status = OutcomeStatus::NoSlope;
    o.problem = r->problem;
  }
  o.values = {{"drained_angle", r->angle_deg}, {"drained_fraction", r->drained_fraction},
              {"settle_time", r->settle_time}, {"particles_left", double(r->particles_left)}};
  OrderedJson& j = o.json;
  j["experiment"] = "drain";
  j["case"] = spec.path;
  j["drained_angle_deg"] = r->sloped ? OrderedJson(r->angle_deg) : OrderedJson(nullptr);
  j["left"] = slope_json(r->heap.left);
  j["right"] = slope_json(r->heap.right);
  j["floor_z"] = r->floor_z;
  j["drained_fraction"] = r->drained_fraction;
  j["particles_left"] = r->particles_left;
  j["settle_time"] = r->settle_time;
  o.files.push_back(text_file("heap.csv", [r](std::ostream& out) {
    out << "x_m,y_m,z_m,radius_m\n";
    for (const auto& s : r->spheres) out << s.centre.x << "," << s.centre.y << "," << s.centre.z << "," << s.radius << "\n";
  }));
  std::string horizontal = settings_of<DrainSettings>(spec.experiment).view == "x" ? "y" : "x";
  HeapPictureCaption caption = slope_caption(r->heap, r->side);
  o.files.push_back({"heap.png", [r, horizontal, caption](const std::string& path) {
                       write_heap_angle_png(path, r->heap, horizontal, caption);
                     }});
  if (r->sloped)
    o.lines.push_back(printf_text("drain %s: drained angle of repose %.2f deg, %.1f %% of the particles drained, %zu left, "
                                "settled at %.3g s",
                                spec.name.c_str(), r->angle_deg, 100 * r->drained_fraction, r->particles_left,
                                r->settle_time));
  return o;
}

const Experiment& drain_experiment() {
  static const DrainExperiment experiment;
  return experiment;
}

}  // namespace repose
