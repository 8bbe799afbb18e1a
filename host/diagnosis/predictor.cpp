#include "diagnosis/predictor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "case/case_loader.h"
#include "case/particle_factory.h"
#include "diagnosis/heap_bed.h"
#include "diagnosis/heap_fill.h"
#include "diagnosis/heap_measures.h"
#include "diagnosis/impact_phase.h"
#include "experiments/repose.h"
#include "experiments/roll.h"
#include "experiments/tilt.h"

namespace repose {

Predictor::Predictor(const Observations& obs, std::vector<CaseOverride> given, bool fit_baseline,
                     unsigned threads, int simulated_replicates)
    : obs_(obs), fit_baseline_(fit_baseline), threads_(std::max(1u, threads)),
      replicates_(std::max(2, simulated_replicates)) {
  for (const Condition& c : obs.conditions) {
    std::vector<CaseOverride> sets = given;
    sets.insert(sets.end(), c.sets.begin(), c.sets.end());
    CaseSpec spec = load_case(c.case_path, sets);
    const DiagnosedExperiment* kind = diagnosed_experiment(spec);
    if (!kind)
      throw DataError(obs.path + ": case " + c.case_path + " runs experiment '" + spec.experiment.type +
                      "': diagnose simulates drop, slide, roll (incline or tilt) and repose (heap) tests");
    if (!experiment_) experiment_ = kind;
    if (kind != experiment_)
      throw DataError(obs.path + ": case " + c.case_path + " runs '" + kind->id + "' but an earlier row's case runs '" +
                      experiment_->id + "': one diagnosis compares one experiment");
    if (kind->id == "drop") {
      if (!spec.bodies.empty() || spec.spheres.size() != 1)
        throw DataError(obs.path + ": case " + c.case_path +
                        ": diagnose drops one sphere (a clump body is what the `shape` extension tests; the other "
                        "extensions' drop physics and the impact-time alignment are written for a sphere)");
      body_plate_interaction(spec);  // the body-plate contact must exist
    } else if (kind->id == "repose") {
      bool sphere_fills = !spec.fills.empty();
      size_t filled = 0;
      for (const FillSpec& f : spec.fills) {
        sphere_fills = sphere_fills && f.template_index < 0;
        filled += size_t(f.count);
      }
      if (!sphere_fills || !spec.lattices.empty() || !spec.bodies.empty() || spec.spheres.size() != filled)
        throw DataError(obs.path + ": case " + c.case_path +
                        ": diagnose fills heaps from sphere [[fill]]s only (no [[sphere]], [[lattice]] or clumps), "
                        "so that replicates and size spreads can refill them");
      heap_interaction(spec);  // the grain-grain contact must exist
      spec.spheres.clear();    // refilled per model and replicate (model_spec)
    } else {
      bool one_body = spec.fills.empty() && spec.lattices.empty() &&
                      ((spec.spheres.size() == 1 && spec.bodies.empty()) || (spec.spheres.empty() && spec.bodies.size() == 1));
      if (!one_body)
        throw DataError(obs.path + ": case " + c.case_path + ": diagnose tilts or rolls one body (one [[sphere]] or one "
                        "[[clump]], no fills or lattices)");
      body_plate_interaction(spec);  // the body-plate contact must exist
    }
    specs_.push_back(std::move(spec));
  }
  for (const auto& g : obs.groups) {
    const auto& ms = experiment_->measures;
    if (std::find(ms.begin(), ms.end(), g.measure) != ms.end()) continue;
    std::string list;
    for (const auto& e : diagnosed_experiments()) {
      std::string names;
      for (const auto& m : e.measures) names += (names.empty() ? "" : ", ") + m;
      list += (list.empty() ? "" : "; ") + e.id + ": " + names;
    }
    throw DataError(obs.path + ":" + std::to_string(g.line) + ": measure '" + g.measure + "' is not reported by the " +
                    experiment_->id + " experiment diagnose simulates (" + list + ")");
  }
}

std::vector<FreeParameter> Predictor::parameters(const ModelExtension* extension) const {
  std::vector<FreeParameter> p;
  if (fit_baseline_) p.push_back(experiment_->baseline);
  if (extension) {
    std::vector<FreeParameter> own =
        extension->parameters_for ? extension->parameters_for(specs_.front()) : extension->parameters;
    p.insert(p.end(), own.begin(), own.end());
  }
  return p;
}

double Predictor::case_baseline_value() const {
  CaseSpec spec = specs_.front();
  return experiment_->baseline_value(spec);
}

CaseSpec Predictor::model_spec(size_t condition, const ModelExtension* extension, const std::vector<double>& params,
                               int replicate) const {
  CaseSpec spec = specs_[condition];
  size_t k = 0;
  if (fit_baseline_) experiment_->baseline_value(spec) = params.at(k++);
  if (extension) extension->apply(spec, std::vector<double>(params.begin() + k, params.end()));
  spec.seed += uint64_t(replicate);  // a clump's orientation (run_drop draws it from the seed)
  if (experiment() == "repose") {
    for (FillSpec& f : spec.fills) f.seed += uint64_t(replicate);
    HeapFill how = fill_heap(spec);  // a fill too tight for the model's grains is placed again (heap_fill.h)
    std::lock_guard<std::mutex> lock(fill_mutex_);
    FillRecord& record = fills_[extension ? extension->id : "baseline"];
    ++record.heaps;
    if (how.fallback) ++record.fallback;
    record.most_raised = std::max(record.most_raised, how.raised);
  }
  return spec;
}

bool Predictor::stochastic(const ModelExtension* extension, const std::vector<double>& params) const {
  if (experiment() == "repose") return true;
  if (experiment() != "drop") return false;  // a tilt or roll test places its body as the case says
  return !model_spec(0, extension, params, 0).bodies.empty();
}

Outcome Predictor::simulate(size_t condition, const ModelExtension* extension, const std::vector<double>& params,
                            int replicate) {
  std::string key = std::to_string(condition) + "|" + std::to_string(replicate) + "|" +
                    (extension ? extension->id : "baseline");
  for (double v : params) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "|%a", v);
    key += buf;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
  }
  CaseSpec spec = model_spec(condition, extension, params, replicate);
  Outcome r = experiment() == "drop"     ? run_drop_condition(std::move(spec))
              : experiment() == "repose" ? run_heap_condition(spec)
                                         : run_tilt_or_roll_condition(spec);
  std::lock_guard<std::mutex> lock(mutex_);
  ++simulations_;
  cache_[key] = r;
  return r;
}

Outcome Predictor::run_drop_condition(CaseSpec spec) const {
  // Models far from the data (met while searching) can stop the body on the plate: predict no
  // rebound, a fall in vacuum and rest, so the search moves away from them.
  double g = std::sqrt(spec.gravity[0] * spec.gravity[0] + spec.gravity[1] * spec.gravity[1] +
                       spec.gravity[2] * spec.gravity[2]);
  double fall = std::sqrt(2 * spec.experiment.drop_height / g);
  spec.experiment.max_time = std::min(spec.experiment.max_time, 3 * fall + 0.5);
  align_impact_phase(spec);
  Outcome out;
  try {
    DropResult r = run_drop(spec, DropOptions{});
    out.values["rebound_height"] = r.rebound_height;
    out.values["restitution"] = r.restitution;
    out.trajectory = std::move(r.trajectory);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find("did not rebound") == std::string::npos) throw;
    out.values["rebound_height"] = 0;
    out.values["restitution"] = 0;
    for (int k = 0; k <= 100; ++k) {
      double t = k * 0.01 * spec.experiment.max_time;
      out.trajectory.push_back({t, std::max(0.0, spec.experiment.drop_height - 0.5 * g * t * t)});
    }
  }
  return out;
}

Outcome Predictor::run_heap_condition(const CaseSpec& spec) const {
  Outcome out;
  const auto& measures = observations().measures;
  if (std::all_of(measures.begin(), measures.end(), [](const std::string& m) { return m == "bed_height"; })) {
    out.values["bed_height"] = measure_bed_height(spec);  // the bed alone: no lift, no heap
    return out;
  }
  try {
    ReposeResult r = run_repose(spec, {}, true);  // a lone spinning grain does not change the heap
    out.values = heap_measures(r, spec.experiment.heap_side);
  } catch (const std::exception& e) {
    // A model far from the data (met while searching) whose heap shows no slope or no heap at all
    // (grains so sticky that the soft contacts blow apart): no heap, so the search moves away
    // from it. A heap still moving at max_time is the case's problem: say so.
    bool no_heap = dynamic_cast<const std::invalid_argument*>(&e) ||
                   std::string(e.what()).find("slope") != std::string::npos ||
                   std::string(e.what()).find("no particle is left") != std::string::npos;
    if (!no_heap) throw;
    for (const std::string& m : heap_measure_names()) out.values[m] = 0;
  }
  return out;
}

Outcome Predictor::run_tilt_or_roll_condition(const CaseSpec& spec) const {
  Outcome out;
  if (experiment() == "roll") {
    // A model far from the data (met while searching) may roll on past max_time: predict the
    // distance reached by then, so the search moves away from it.
    RollResult r = run_roll(spec, {}, false);
    out.values["roll_distance"] = r.rolling_distance;
    return out;
  }
  double angle = 0;
  try {
    angle = run_tilt(spec).onset_angle_deg;
  } catch (const std::runtime_error& e) {
    // The body held on up to max_angle: predict max_angle, the most the rig can tell.
    if (std::string(e.what()).find("did not move") == std::string::npos) throw;
    angle = spec.experiment.max_angle_deg;
  }
  out.values[experiment() == "slide" ? "slide_angle" : "roll_angle"] = angle;
  return out;
}

double Predictor::value_of(const ObservationGroup& g, const Outcome& r) const {
  if (!g.series) return r.values.at(g.measure);
  // height: the camera's trajectory, linear between frames.
  const auto& tr = r.trajectory;
  if (g.t < tr.front().first)
    throw DataError(obs_.path + ":" + std::to_string(g.line) + ": t = " + std::to_string(g.t) +
                    " s is before the release (t = 0)");
  if (g.t > tr.back().first) {
    // The simulated drop stops past the rebound apex; from there the body is in free flight
    // (until it lands again, where it stays for this purpose).
    size_t n = tr.size();
    double v = (tr[n - 1].second - tr[n - 2].second) / (tr[n - 1].first - tr[n - 2].first);
    const Vec3d& gv = specs_[g.condition].gravity;
    double gm = std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
    double s = g.t - tr[n - 1].first;
    return std::max(0.0, tr[n - 1].second + v * s - 0.5 * gm * s * s);
  }
  size_t hi = 1;
  while (hi + 1 < tr.size() && tr[hi].first < g.t) ++hi;
  double t0 = tr[hi - 1].first, t1 = tr[hi].first;
  double w = t1 > t0 ? (g.t - t0) / (t1 - t0) : 0.0;
  return tr[hi - 1].second + w * (tr[hi].second - tr[hi - 1].second);
}

Prediction Predictor::predict(const ModelExtension* extension, const std::vector<double>& params,
                              const std::vector<char>& use) {
  size_t nc = obs_.conditions.size();
  int reps = stochastic(extension, params) ? replicates_ : 1;
  std::vector<std::vector<Outcome>> results(nc, std::vector<Outcome>(size_t(reps)));
  std::vector<std::pair<size_t, int>> pending;
  for (size_t c = 0; c < nc; ++c)
    if (use[c])
      for (int r = 0; r < reps; ++r) pending.push_back({c, r});
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&] {
    for (size_t k = next++; k < pending.size(); k = next++) {
      try {
        auto [c, r] = pending[k];
        results[c][size_t(r)] = simulate(c, extension, params, r);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::min<size_t>(threads_, pending.size()); ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  Prediction out;
  out.replicates = reps;
  out.mean.assign(obs_.groups.size(), 0.0);
  out.var.assign(obs_.groups.size(), 0.0);
  for (size_t g = 0; g < obs_.groups.size(); ++g) {
    const ObservationGroup& grp = obs_.groups[g];
    if (!use[grp.condition]) continue;
    double sum = 0, sum2 = 0;
    std::vector<double> v;
    for (const Outcome& r : results[grp.condition]) v.push_back(value_of(grp, r));
    for (double x : v) sum += x;
    double mean = sum / reps;
    for (double x : v) sum2 += (x - mean) * (x - mean);
    out.mean[g] = mean;
    out.var[g] = reps > 1 ? sum2 / (reps - 1) : 0.0;
  }
  return out;
}

}  // namespace repose
