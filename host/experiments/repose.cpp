#include "experiments/experiment_simulation.h"
#include "experiments/repose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "engine/backend_factory.h"
#include "engine/kinetic_energy.h"
#include "engine/model.h"
#include "case/case_error.h"
#include "case/particle_factory.h"
#include "engine/simulation.h"
#include "experiments/body_frame.h"
#include "experiments/heap_fill.h"
#include "experiments/experiment_checkpoint.h"
#include "measure/bed_height.h"
#include "measure/heap_grains.h"
#include "measure/heap_json.h"
#include "measure/heap_png.h"
#include "util/atomic_file.h"
#include "util/progress.h"

namespace repose {

namespace {

// Twice the volume-weighted mean height of the grains above the floor (measure/bed_height.h).
double bed_height(const HostState& st, const std::optional<double>& floor) {
  std::vector<Sphere> grains;
  grains.reserve(st.pos.size());
  for (const auto& p : st.pos) grains.push_back({{p.x, p.y, p.z}, p.w});
  return uniform_bed_height(grains, floor);
}

}  // namespace

namespace {

// When the lifted wall stops: [experiment] lift_end, else the end of its motion; before max_time.
double lift_end_of(const CaseSpec& spec, const WallSpec& lift) {
  const ReposeSettings& ex = settings_of<ReposeSettings>(spec.experiment);
  double lift_end = ex.lift_end > 0 ? ex.lift_end : lift.motion.stop_time;
  if (!(lift_end < 1e29))
    throw CaseError(lift.where, "the wall '" + lift.name + "' moves without a stop time: give [experiment] lift_end");
  if (lift_end >= spec.experiment.max_time)
    throw CaseError(spec.experiment.max_time_where, format_number(spec.experiment.max_time) +
                                                        " s must exceed the end of the lift (" +
                                                        format_number(lift_end) + " s)");
  return lift_end;
}

// What the progress line expects: the fill ends at the lift's start; the lift at lift_end, or
// sooner with end_when_clear once the lifted wall's force, falling as it rises, reaches zero; the
// run-out once the largest kinetic energy, decaying exponentially, falls below settle_energy.
struct HeapEta {
  FallingTrend wall_force{1.0, false}, energy{1.0, true};
  void tell(Progress& progress, const ReposeSettings& ex, const WallSpec& lift, double lift_end, size_t phase,
            double t, double force, double e) {
    static const char* names[] = {"fill", "lift", "run-out"};
    progress.set_label(names[phase]);
    if (phase == 2) {
      energy.add(t, e);
      double settled = energy.reaches(ex.settle_energy);
      if (settled < 0) progress.expect_unknown_end("(until settled: not yet calming)");
      else progress.expect_end_time(settled, "(until settled)");
      return;
    }
    double end = lift_end;
    if (phase == 1 && ex.end_when_clear) {
      wall_force.add(t, force);
      double clear = wall_force.reaches(0.0);
      // A trend that put the clearing in the past while the wall still touches grains (a gate
      // slid aside under a stream that still brushes it) says nothing: the lift's end holds.
      if (clear > t) end = std::min(end, clear);
    }
    progress.expect_end_time(end, phase == 0 ? printf_text("(filling to %g s, then the lift: at most to %g s%s)",
                                                           lift.motion.start_time, lift_end,
                                                           ex.end_when_clear ? ", sooner once clear of the heap" : "")
                                             : "(the lift's end, then the run-out)");
  }
};

// What run_until_settled has gathered by a sample, as its checkpoints keep it (experiment_checkpoint.h).
OrderedJson repose_progress(const ReposeResult& r, bool bed_measured, bool clear_before) {
  OrderedJson energy = OrderedJson::array(), phases = OrderedJson::array();
  for (const auto& [t, e] : r.energy) energy.push_back({t, e});
  for (const auto& [name, p] : r.phases) phases.push_back({name, profile_json(p)});
  return {{"bed_measured", bed_measured}, {"bed_height_m", r.bed_height}, {"clear_before", clear_before},
          {"energy", energy},             {"wall_forces", wall_series_json(r.wall_forces)},
          {"phases", phases}};
}

void load_repose_progress(const OrderedJson& j, ReposeResult& r, bool& bed_measured, bool& clear_before) {
  bed_measured = j.at("bed_measured").get<bool>();
  r.bed_height = j.at("bed_height_m").get<double>();
  clear_before = j.at("clear_before").get<bool>();
  for (const auto& e : j.at("energy")) r.energy.push_back({e.at(0).get<double>(), e.at(1).get<double>()});
  r.wall_forces = wall_series_from_json(j.at("wall_forces"));
  r.phases.clear();
  for (const auto& p : j.at("phases")) r.phases.push_back({p.at(0).get<std::string>(), profile_from_json(p.at(1))});
}

// Fill, lift and run-out, sampled every 0.05 s, until the lift is over (or the lifted wall clear
// of the heap twice running) and no particle is faster than settle_energy; the bed height when
// the lift starts, energies, wall forces and the time per phase go into r. Not settled by
// max_time: r.settled false (an error unless measure_unsettled), with everything so far.
void run_until_settled(const CaseSpec& spec, const ExperimentRunOptions& options, const WallSpec& lift,
                       double lift_end, bool measure_unsettled, Simulation& sim, ReposeResult& r) {
  const ReposeSettings& ex = settings_of<ReposeSettings>(spec.experiment);
  uint64_t sample_steps = steps_in(0.05, r.dt);
  HeapEta eta;
  // The lifted wall's entry among the named walls (its force tells when it is clear of the heap).
  auto names = sim.model().wall_group_names();
  size_t lift_group = size_t(std::find(names.begin(), names.end(), lift.name) - names.begin());
  bool clear_before = false, bed_measured = false;
  r.phases = {{"fill", {}}, {"lift", {}}, {"run-out", {}}};
  ExperimentCheckpoints checkpoints(options, spec, "repose");
  if (auto saved = checkpoints.restore(sim)) load_repose_progress(*saved, r, bed_measured, clear_before);
  Progress progress(spec.name + " repose", uint64_t(spec.experiment.max_time / r.dt) + 1, r.dt, options.progress,
                    sim.step());
  while (true) {
    auto sample_start = std::chrono::steady_clock::now();
    size_t phase = sim.time() < lift.motion.start_time - 1e-9 ? 0 : sim.time() < lift_end - 1e-9 ? 1 : 2;
    sim.advance(sample_steps);
    if (!bed_measured && sim.time() >= lift.motion.start_time - 1e-9) {
      r.bed_height = bed_height(sim.state(), ex.heap_floor_z);
      bed_measured = true;
    }
    double e = largest_kinetic_energy(sim);
    r.energy.push_back({sim.time(), e});
    r.wall_forces.sample(sim);
    RunProfile sample = sim.take_profile();
    sample.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sample_start).count();
    r.phases[phase].second.add(sample);
    const WallForce& f = r.wall_forces.rows.back().at(lift_group);
    bool clear = sim.time() > lift.motion.start_time && f.fx == 0 && f.fy == 0 && f.fz == 0;
    bool lift_over = sim.time() >= lift_end || (ex.end_when_clear && clear && clear_before);
    clear_before = clear;
    eta.tell(progress, ex, lift, lift_end, lift_over ? 2 : phase, sim.time(), std::sqrt(f.fx * f.fx + f.fy * f.fy + f.fz * f.fz), e);
    progress.update(sim.step(), printf_text("largest kinetic energy %.3g J", e));
    bool out_of_time = sim.time() >= spec.experiment.max_time;
    if ((lift_over && e < ex.settle_energy) || out_of_time) {
      r.settle_time = sim.time();
      r.kinetic_energy = e;
      r.settled = !out_of_time || (lift_over && e < ex.settle_energy);
      break;
    }
    checkpoints.after_sample(sim, [&] { return repose_progress(r, bed_measured, clear_before); });
  }
  r.checkpoints_written = checkpoints.written();
  r.checkpoint_seconds = checkpoints.write_seconds();
  progress.finish();
  if (!r.settled) {
    r.problem = spec.path + ": the heap had not settled (largest kinetic energy " + format_number(r.kinetic_energy) +
                " J of a particle, settle_energy " + format_number(ex.settle_energy) + ") by max_time = " +
                format_number(spec.experiment.max_time) + " s";
    if (!measure_unsettled) throw std::runtime_error(r.problem);
  }
}

// The heap's particles: those whose bottom is not below the heap floor (those that fell off a
// plate or out of a bucket are not in the picture) and that rest on it, directly or through
// others (those left on a hopper or a gate above the heap are not either:
// measure/heap_grains.h). Returns the floor used.
double collect_heap(const CaseSpec& spec, const HostState& state, ReposeResult& r) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto& p : state.pos) lowest = std::min(lowest, double(p.z) - p.w);
  double floor_z = settings_of<ReposeSettings>(spec.experiment).heap_floor_z.value_or(lowest);
  std::vector<uint32_t> body_of(state.bodies.empty() ? 0 : state.pos.size());  // clumps rest as a whole
  for (uint32_t b = 0; b < state.bodies.size(); ++b)
    for (uint32_t k = 0; k < state.bodies[b].spheres.y; ++k) body_of[state.bodies[b].spheres.x + k] = b;
  std::vector<Sphere> above;
  std::vector<uint32_t> above_bodies;
  for (size_t i = 0; i < state.pos.size(); ++i) {
    const auto& p = state.pos[i];
    if (double(p.z) - p.w < floor_z - 0.5 * p.w) continue;
    above.push_back({{p.x, p.y, p.z}, p.w});
    if (!body_of.empty()) above_bodies.push_back(body_of[i]);
  }
  r.particles_apart = keep_resting(above, floor_z, above_bodies);
  r.spheres = std::move(above);
  r.particles_measured = r.spheres.size();
  if (r.spheres.empty()) throw std::runtime_error(spec.path + ": no particle is left above the heap floor");
  return floor_z;
}

// The studies' picture measurement of r.spheres: the slope on [experiment] heap_side (or both),
// around the heap in `views` views, and the 3D sector fit. No slope: an error, or (require_slope
// off) a result with angle 0 that says why.
void measure_heap(const CaseSpec& spec, double floor_z, bool require_slope, ReposeResult& r) {
  const ReposeSettings& ex = settings_of<ReposeSettings>(spec.experiment);
  HeapAngleOptions opts;
  opts.view = ex.view == "x" ? ViewAxis::X : ViewAxis::Y;
  opts.floor_z = floor_z;
  opts.visible_from = ex.visible_from;
  r.heap = measure_heap_angle(r.spheres, opts);
  r.profile = measure_heap_profile(r.heap);
  auto no_slope = [&](const std::string& problem) {
    if (require_slope) throw std::runtime_error(spec.path + ": " + problem);
    r.sloped = false;
    r.problem = spec.path + ": " + problem;
    r.angle_deg = 0;
  };
  const SlopeFit* side = ex.heap_side == "left" ? &r.heap.left : ex.heap_side == "right" ? &r.heap.right : nullptr;
  if (side && !side->valid) return no_slope("no " + ex.heap_side + " slope: " + side->problem);
  if (!side && !r.heap.left.valid && !r.heap.right.valid)
    return no_slope("the heap has no measurable slope (" + r.heap.left.problem + ")");
  r.angle_deg = side ? side->angle_deg : r.heap.mean_deg;
  if (ex.views > 1) {
    r.views = measure_heap_angle_views(r.spheres, ex.views, opts);
    if (r.views->valid_slopes == 0) return no_slope("no view of the heap shows a measurable slope");
    r.angle_deg = r.views->mean_deg;
  }
  if (ex.axisymmetric) {
    AxisymmetricOptions a;
    a.floor_z = floor_z;
    r.heap_3d = measure_axisymmetric_heap_angle(r.spheres, a);
  }
}

}  // namespace

ReposeResult run_repose(const CaseSpec& spec, const ExperimentRunOptions& options, bool measure_unsettled,
                        bool require_slope) {
  const WallSpec& lift = spec.walls.at(find_wall(spec, settings_of<ReposeSettings>(spec.experiment).lift_wall, "lifted wall"));
  double lift_end = lift_end_of(spec, lift);  // a case error before anything is built
  Model model = build_model(spec);
  Simulation sim = experiment_simulation(model, options, steps_in(0.05, model.dt), 200);
  sim.set_profiling(options.profile);
  ReposeResult r;
  r.dt = model.dt;
  run_until_settled(spec, options, lift, lift_end, measure_unsettled, sim, r);
  double floor_z = collect_heap(spec, sim.state(), r);
  measure_heap(spec, floor_z, require_slope, r);
  return r;
}

double measure_bed_height(const CaseSpec& spec) {
  const ReposeSettings& ex = settings_of<ReposeSettings>(spec.experiment);
  const WallSpec& lift = spec.walls.at(find_wall(spec, ex.lift_wall, "lifted wall"));
  Model model = build_model(spec);
  // run_repose's sampling: batches of 0.05 s, the bed taken at the first sample at the lift.
  uint64_t sample_steps = steps_in(0.05, model.dt);
  Simulation sim = experiment_simulation(model, {}, sample_steps, 200);
  do sim.advance(sample_steps);
  while (sim.time() < lift.motion.start_time - 1e-9);
  return bed_height(sim.state(), ex.heap_floor_z);
}

const std::vector<std::string>& heap_measure_names() {
  static const std::vector<std::string> names = {"repose_angle", "bed_height", "heap_height", "runout",
                                                 "profile_convexity"};
  return names;
}

std::map<std::string, double> heap_measures(double angle_deg, double bed_height, const HeapProfile& profile,
                                            const std::string& heap_side) {
  std::vector<const SlopeProfile*> sides;
  if (heap_side != "right") sides.push_back(&profile.left);
  if (heap_side != "left") sides.push_back(&profile.right);
  double runout = 0, convexity = 0;
  for (const SlopeProfile* s : sides) {
    runout += s->runout / double(sides.size());
    if (s->valid) convexity += s->convexity / double(sides.size());
  }
  return {{"repose_angle", angle_deg},
          {"bed_height", bed_height},
          {"heap_height", profile.height},
          {"runout", runout},
          {"profile_convexity", convexity}};
}

std::map<std::string, double> heap_measures(const ReposeResult& heap, const std::string& heap_side) {
  return heap_measures(heap.angle_deg, heap.bed_height, heap.profile, heap_side);
}

std::vector<std::string> repose_keys() {
  return {"lift_wall", "lift_end", "end_when_clear", "settle_energy", "view", "views", "heap_side", "axisymmetric", "floor_z",
          "visible_from"};
}

std::shared_ptr<const ExperimentSettings> read_repose_keys(const Section& s) {
  auto settings = std::make_shared<ReposeSettings>();
  ReposeSettings& ex = *settings;
  ex.lift_wall = s.text("lift_wall").value_or("");
  if (ex.lift_wall.empty()) s.missing("lift_wall", " (the name of the [[wall]] that is lifted or pulled)");
  if (auto t = s.number("lift_end")) ex.lift_end = non_negative(s, "lift_end", *t);
  ex.end_when_clear = s.boolean("end_when_clear").value_or(true);
  if (auto e = s.number("settle_energy")) ex.settle_energy = positive(s, "settle_energy", *e);
  ex.view = s.choice<std::string>("view", {{"x", "x"}, {"y", "y"}}, ex.view);
  ex.heap_side = s.choice<std::string>("heap_side", {{"left", "left"}, {"right", "right"}, {"both", "both"}}, ex.heap_side);
  ex.axisymmetric = s.boolean("axisymmetric").value_or(false);
  if (auto n = s.integer("views")) {
    if (*n < 1 || *n > 180) s.fail("views", std::to_string(*n) + " must lie between 1 and 180");
    ex.views = int(*n);
    if (ex.views > 1 && ex.heap_side != "both")
      s.fail("views", "several views measure both slopes of each: heap_side must be \"both\", not \"" + ex.heap_side + "\"");
  }
  if (auto z = s.number("floor_z")) ex.heap_floor_z = *z;
  if (auto v = s.number("visible_from")) {
    ex.visible_from = *v;
    if (ex.views > 1 || ex.axisymmetric)
      s.fail("visible_from", "hides part of the front view only: it needs views = 1 and axisymmetric = false");
  }
  return settings;
}

// ---------------------------------------------------------------------------------------------
// The registered experiment.

namespace {

// heap.png's title: the headline angle (r.angle_deg) and how it was measured; the front view's
// slopes that count towards it are drawn.
HeapPictureCaption heap_caption(const CaseSpec& spec, const ReposeResult& r) {
  HeapPictureCaption caption = slope_caption(r.heap, settings_of<ReposeSettings>(spec.experiment).heap_side);
  caption.angle_deg = r.sloped ? r.angle_deg : std::numeric_limits<double>::quiet_NaN();
  if (r.views) caption.measured_as = "the mean of " + std::to_string(r.views->azimuth_deg.size()) + " views' slopes";
  const ReposeSettings& ex = settings_of<ReposeSettings>(spec.experiment);
  if (ex.visible_from) {
    char where[64];
    std::snprintf(where, sizeof where, " beyond %s = %.3g m", ex.view == "x" ? "y" : "x", *ex.visible_from);
    caption.measured_as += where;
  }
  if (!r.settled)
    caption.warning = printf_text("not settled at %.3g s", r.settle_time);  // repose.json says more
  return caption;
}

OrderedJson repose_json(const CaseSpec& spec, const ReposeResult& r) {
  OrderedJson j;
  j["experiment"] = "repose";
  j["case"] = spec.path;
  j["heap_side"] = settings_of<ReposeSettings>(spec.experiment).heap_side;
  j["angle_deg"] = r.angle_deg;
  j["angle_measured_as"] = heap_caption(spec, r).measured_as;  // as heap.png's title and the console say
  j["left"] = slope_json(r.heap.left);
  j["right"] = slope_json(r.heap.right);
  j["mean_deg"] = std::isfinite(r.heap.mean_deg) ? OrderedJson(r.heap.mean_deg) : OrderedJson(nullptr);
  j["heap_height"] = r.heap.heap_height;
  j["bed_height"] = r.bed_height;
  j["left_profile"] = profile_json(r.profile.left);
  j["right_profile"] = profile_json(r.profile.right);
  j["floor_z"] = r.heap.floor_z;
  j["particles_measured"] = r.particles_measured;
  j["particles_apart"] = r.particles_apart;
  j["settle_time"] = r.settle_time;
  j["largest_kinetic_energy"] = r.kinetic_energy;
  if (r.views) j["views"] = views_json(*r.views);
  if (r.heap_3d) j["axisymmetric"] = axisymmetric_json(*r.heap_3d);
  OrderedJson phases = OrderedJson::array();
  for (const auto& [name, p] : r.phases)
    phases.push_back({{"phase", name}, {"steps", p.steps}, {"simulated_s", double(p.steps) * r.dt},
                      {"wall_s", p.wall_seconds}, {"rebuilds", p.rebuilds}});
  j["phases"] = phases;
  return j;
}

void add_repose_files(ExperimentOutcome& o, const std::shared_ptr<const ReposeResult>& r, const CaseSpec& spec) {
  o.files.push_back(text_file("energy.csv", [r](std::ostream& out) {
    out << "t_s,largest_kinetic_energy_J\n";
    for (const auto& [t, e] : r->energy) out << t << "," << e << "\n";
  }));
  o.files.push_back(text_file("heap.csv", [r](std::ostream& out) {
    out << "x_m,y_m,z_m,radius_m\n";
    for (const auto& s : r->spheres) out << s.centre.x << "," << s.centre.y << "," << s.centre.z << "," << s.radius << "\n";
  }));
  if (!r->wall_forces.rows.empty())
    o.files.push_back(text_file("wall_forces.csv", [r](std::ostream& out) { r->wall_forces.write_csv(out); }));
  std::string horizontal = settings_of<ReposeSettings>(spec.experiment).view == "x" ? "y" : "x";  // the picture's horizontal axis
  HeapPictureCaption caption = heap_caption(spec, *r);
  o.files.push_back({"heap.png", [r, horizontal, caption](const std::string& path) {
                       write_heap_angle_png(path, r->heap, horizontal, caption);
                     }});
}

// With --profile: where each phase's time went, by kernel stage and by kernel.
std::vector<std::string> profile_lines(const std::string& backend, const ReposeResult& r) {
  std::vector<std::string> lines{"where the time went (" + backend + "):"};
  std::string table = format_profiles(r.phases, r.dt);
  for (size_t start = 0, end; start < table.size(); start = end + 1) {
    end = table.find('\n', start);
    lines.push_back(table.substr(start, end - start));
  }
  for (const auto& [name, p] : r.phases)
    if (p.steps) {
      lines.push_back("  " + name + " kernels per step: " + format_kernel_times(p));
      lines.push_back("  " + name + " " + format_host_times(p));
    }
  if (r.checkpoints_written > 0)
    lines.push_back(printf_text("  checkpoints (outside the phases): %llu written in %.3g s, %.3g s each (the state "
                                "read back, put in global order and written)",
                                (unsigned long long)r.checkpoints_written, r.checkpoint_seconds,
                                r.checkpoint_seconds / double(r.checkpoints_written)));
  return lines;
}

std::vector<std::string> repose_lines(const CaseSpec& spec, const ReposeResult& r) {
  auto side = [](const SlopeFit& s) { return s.valid ? std::to_string(s.angle_deg).substr(0, 5) + " deg" : std::string("none"); };
  std::vector<std::string> lines;
  std::string angle = std::isfinite(r.angle_deg) ? printf_text("%.2f deg", r.angle_deg) : "not measured (no valid slope)";
  // The headline as heap.png's title states it: the number, how it was measured, then the front view.
  lines.push_back(printf_text("repose %s: angle of repose %s (%s; front view: left %s, right %s), heap %.3g m high, "
                              "%zu particles",
                              spec.name.c_str(), angle.c_str(), heap_caption(spec, r).measured_as.c_str(),
                              side(r.heap.left).c_str(), side(r.heap.right).c_str(), r.heap.heap_height,
                              r.particles_measured));
  for (const auto& [side, p] : {std::pair{"left", &r.profile.left}, std::pair{"right", &r.profile.right}})
    lines.push_back(printf_text("  %s side: run-out %.3g m, convexity %s", side, p->runout,
                                p->valid ? printf_text("%+.3f", p->convexity).c_str() : ("none (" + p->problem + ")").c_str()));
  if (r.particles_apart)
    lines.push_back(printf_text("  %zu particles above the floor but apart from the heap (left on walls above it) "
                                "are not measured",
                                r.particles_apart));
  lines.push_back(printf_text("  bed before the lift: %.4g m high", r.bed_height));
  if (r.views) lines.push_back("  views around the heap (the angle): " + describe_views(*r.views));
  if (r.heap_3d) lines.push_back("  3D sector fit: " + describe_sector_fit(*r.heap_3d));
  return lines;
}

}  // namespace

std::vector<std::string> ReposeExperiment::responses() const {
  return {"angle", "angle_3d", "angle_front", "angle_views_sd", "heap_height", "settle_time", "particles_measured"};
}

ExperimentOutcome ReposeExperiment::run(const CaseSpec& spec, const ExperimentRun& run) const {
  // Not strict: a heap unsettled at max_time or without a slope is measured as it stands and
  // reported with that status.
  auto r = std::make_shared<const ReposeResult>(run_repose(spec, run, !run.strict, run.strict));
  ExperimentOutcome o;
  if (!r->settled || !r->sloped) {
    o.status = r->settled ? OutcomeStatus::NoSlope : OutcomeStatus::NotSettled;
    o.problem = r->problem;
  }
  if (!run.picture_path.empty())
    write_heap_angle_png(run.picture_path, r->heap, settings_of<ReposeSettings>(spec.experiment).view == "x" ? "y" : "x", heap_caption(spec, *r));
  o.values = {{"angle", r->angle_deg}, {"heap_height", r->heap.heap_height}, {"settle_time", r->settle_time},
              {"particles_measured", double(r->particles_measured)}};
  if (r->heap_3d && r->heap_3d->valid_sectors > 0) o.values["angle_3d"] = r->heap_3d->mean_deg;
  o.values["angle_front"] = r->heap.mean_deg;  // the single front view, also when the angle is several views' mean
  if (r->views) o.values["angle_views_sd"] = r->views->sd_deg;
  o.json = repose_json(spec, *r);
  add_repose_files(o, r, spec);
  o.lines = repose_lines(spec, *r);
  if (run.profile)
    for (const std::string& line : profile_lines(run.backend, *r)) o.lines.push_back(line);
  return o;
}

void ReposeExperiment::check_case(const CaseSpec& spec) const {
  const std::string& name = settings_of<ReposeSettings>(spec.experiment).lift_wall;
  for (const WallSpec& wall : spec.walls) {  // find_wall's choice; without one, run() says so
    if (name.empty() || wall.name == name) {
      lift_end_of(spec, wall);
      return;
    }
  }
}

const DiagnosisRole* ReposeExperiment::diagnosis() const {
  static const DiagnosisRole role = [] {
    DiagnosisRole r;
    r.measures = {{"repose_angle", false, "deg"}, {"bed_height", false, "m"},  {"heap_height", false, "m"},
                  {"runout", false, "m"},         {"profile_convexity", false, "1"}};
    r.synthetic = {"repose_angle", "bed_height"};
    r.baseline = {"static_friction", "1", 0.05, 1.2, false};
    r.baseline_field = &Interaction::static_friction;
    r.baseline_model = "Hertz-Mindlin, one grain size, constant rolling torque";
    r.condition = "fill.0.count";
    r.truth_option = "grain_friction";
    r.separating = SeparatingMeasurement::Packing;
    r.expensive = true;  // a heap costs ~1000 drops
    return r;
  }();
  return &role;
}

// The grains' contact with each other: the first [[fill]]'s material with itself.
Interaction& ReposeExperiment::tested_contact(CaseSpec& spec) const {
  if (spec.fills.empty()) throw std::runtime_error(spec.path + ": the case has no [[fill]] of grains");
  int a = spec.fills[0].material;
  for (auto& in : spec.interactions)
    if (in.material_a == a && in.material_b == a) return in;
  throw std::runtime_error(spec.path + ": no [[interaction]] of the grains' material with itself");
}

std::string ReposeExperiment::diagnosis_problem(const CaseSpec& spec) const {
  bool sphere_fills = !spec.fills.empty();
  size_t filled = 0;
  for (const FillSpec& f : spec.fills) {
    sphere_fills = sphere_fills && f.template_index < 0;
    filled += size_t(f.count);
  }
  if (sphere_fills && spec.lattices.empty() && spec.bodies.empty() && spec.spheres.size() == filled) return "";
  return "diagnose fills heaps from sphere [[fill]]s only (no [[sphere]], [[lattice]] or clumps), so that replicates "
         "and size spreads can refill them";
}

// A fill too tight for a model's grains is placed again (heap_fill.h); the spec's fills say how.
void ReposeExperiment::replicate(CaseSpec& spec, int r) const {
  spec.seed += uint64_t(r);
  for (FillSpec& f : spec.fills) f.seed += uint64_t(r);
  fill_heap(spec);
}

void ReposeExperiment::reseed(CaseSpec& spec, uint64_t seed) const {
  for (FillSpec& f : spec.fills) f.seed = seed;
  fill_heap(spec);
}

DiagnosticOutcome ReposeExperiment::simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>& wanted,
                                                           bool strict) const {
  DiagnosticOutcome out;
  if (std::all_of(wanted.begin(), wanted.end(), [](const std::string& m) { return m == "bed_height"; })) {
    out.values["bed_height"] = measure_bed_height(spec);  // the bed alone: no lift, no heap
    return out;
  }
  // A lone grain that keeps spinning on the floor does not change the heap: measured unsettled.
  // A model far from the data (met while searching) whose heap shows no slope, or no heap at all
  // (grains so sticky that the soft contacts blow apart): no heap (zeros), so the search moves
  // away from it.
  try {
    ReposeResult r = run_repose(spec, {}, true, strict);
    if (r.sloped) {
      out.values = heap_measures(r, settings_of<ReposeSettings>(spec.experiment).heap_side);
      return out;
    }
  } catch (const std::exception& e) {
    bool no_heap = dynamic_cast<const std::invalid_argument*>(&e) ||
                   std::string(e.what()).find("no particle is left") != std::string::npos;
    if (strict || !no_heap) throw;
  }
  for (const std::string& m : heap_measure_names()) out.values[m] = 0;
  return out;
}

// Lengths a thousand times the rig's size are millimetres written as metres.
std::string ReposeExperiment::implausible(const MeasureInfo& m, double value, const CaseSpec& spec) const {
  double fill_height = 0;  // the tallest [[fill]] region: a bed cannot stand higher
  for (const FillSpec& f : spec.fills)
    fill_height = std::max(fill_height, f.shape == FillSpec::Shape::Box ? f.box_max[2] - f.box_min[2] : f.cyl_height);
  if (m.unit != "m" || !(fill_height > 0) || !(value > 10 * fill_height)) return "";
  return std::to_string(value) + " m is more than ten times the fill region's height " + std::to_string(fill_height) +
         " m: millimetres? Values are in SI units (m)";
}

const Experiment& repose_experiment() {
  static const ReposeExperiment repose;
  return repose;
}

}  // namespace repose
