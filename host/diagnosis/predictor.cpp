#include "diagnosis/predictor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "case/case_loader.h"
#include "experiments/registry.h"
#include "util/parallel_each.h"

namespace repose {

Predictor::Predictor(const Observations& obs, std::vector<CaseOverride> given, bool fit_baseline,
                     unsigned threads, int simulated_replicates)
    : obs_(obs), fit_baseline_(fit_baseline), threads_(std::max(1u, threads)),
      replicates_(std::max(2, simulated_replicates)) {
  for (const Condition& c : obs.conditions) {
    std::vector<CaseOverride> sets = given;
    sets.insert(sets.end(), c.sets.begin(), c.sets.end());
    CaseSpec spec = load_case(c.case_path, sets);
    const Experiment* kind = experiment_for(spec);
    if (!kind || !kind->diagnosis()) {
      std::string simulated;
      for (const Experiment* e : experiments())
        if (e->diagnosis()) simulated += (simulated.empty() ? "" : ", ") + e->id();
      throw DataError(obs.path + ": case " + c.case_path + " runs experiment '" + spec.experiment.type +
                      "': diagnose simulates " + simulated);
    }
    if (!experiment_) experiment_ = kind;
    if (kind != experiment_)
      throw DataError(obs.path + ": case " + c.case_path + " runs '" + kind->id() + "' but an earlier row's case runs '" +
                      experiment_->id() + "': one diagnosis compares one experiment");
    std::string problem = kind->diagnosis_problem(spec);
    if (!problem.empty()) throw DataError(obs.path + ": case " + c.case_path + ": " + problem);
    kind->tested_contact(spec);  // the contact the baseline fits must exist
    kind->prepare_for_diagnosis(spec);
    specs_.push_back(std::move(spec));
  }
  role_ = experiment_->diagnosis();
  check_measures();
}

void Predictor::check_measures() const {
  for (const auto& g : obs_.groups) {
    const auto& ms = role_->measures;
    if (std::any_of(ms.begin(), ms.end(), [&](const MeasureInfo& m) { return m.name == g.measure; })) continue;
    std::string list;
    for (const Experiment* e : experiments()) {
      if (!e->diagnosis()) continue;
      std::string names;
      for (const auto& m : e->diagnosis()->measures) names += (names.empty() ? "" : ", ") + m.name;
      list += (list.empty() ? "" : "; ") + e->id() + ": " + names;
    }
    throw DataError(obs_.path + ":" + std::to_string(g.line) + ": measure '" + g.measure + "' is not reported by the " +
                    experiment_->id() + " experiment diagnose simulates (" + list + ")");
  }
}

std::vector<FreeParameter> Predictor::parameters(const ModelExtension* extension) const {
  std::vector<FreeParameter> p;
  if (fit_baseline_) p.push_back(role_->baseline);
  if (extension) {
    std::vector<FreeParameter> own =
        extension->parameters_for ? extension->parameters_for(specs_.front()) : extension->parameters;
    p.insert(p.end(), own.begin(), own.end());
  }
  return p;
}

double Predictor::case_baseline_value() const {
  CaseSpec spec = specs_.front();
  return experiment_->tested_contact(spec).*role_->baseline_field;
}

CaseSpec Predictor::model_spec(size_t condition, const ModelExtension* extension, const std::vector<double>& params,
                               int replicate) const {
  CaseSpec spec = specs_[condition];
  size_t k = 0;
  if (fit_baseline_) experiment_->tested_contact(spec).*role_->baseline_field = params.at(k++);
  if (extension) extension->apply(spec, std::vector<double>(params.begin() + k, params.end()));
  experiment_->replicate(spec, replicate);  // a clump's orientation, a heap's fill
  record_fill(condition, extension, spec);
  return spec;
}

void Predictor::record_fill(size_t condition, const ModelExtension* extension, const CaseSpec& spec) const {
  if (spec.fills.empty()) return;
  std::lock_guard<std::mutex> lock(fill_mutex_);
  FillRecord& record = fills_[extension ? extension->id : "baseline"];
  ++record.heaps;
  const CaseSpec& original = specs_[condition];
  bool fallback = false;
  for (size_t k = 0; k < spec.fills.size(); ++k) {
    const FillSpec &f = spec.fills[k], &o = original.fills[k];
    fallback = fallback || f.largest_first;
    for (int axis = 0; axis < 3; ++axis) {
      double extent = o.box_max[axis] - o.box_min[axis];
      double raised = std::max(f.box_max[axis] - o.box_max[axis], o.box_min[axis] - f.box_min[axis]);
      if (extent > 0 && raised > 0) record.most_raised = std::max(record.most_raised, raised / extent);
    }
  }
  if (fallback) ++record.fallback;
}

bool Predictor::stochastic(const ModelExtension* extension, const std::vector<double>& params) const {
  CaseSpec spec = specs_[0];
  size_t k = 0;
  if (fit_baseline_) experiment_->tested_contact(spec).*role_->baseline_field = params.at(k++);
  if (extension) extension->apply(spec, std::vector<double>(params.begin() + k, params.end()));
  return experiment_->stochastic(spec);
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
  Outcome r = experiment_->simulate_for_diagnosis(std::move(spec), obs_.measures, false);
  std::lock_guard<std::mutex> lock(mutex_);
  ++simulations_;
  cache_[key] = r;
  return r;
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
                              const std::vector<char>& use, int first_replicate, int replicates) {
  size_t nc = obs_.conditions.size();
  bool random = stochastic(extension, params);
  int reps = random ? (replicates > 0 ? replicates : replicates_) : 1;
  int first = random ? first_replicate : 0;
  std::vector<std::vector<Outcome>> results(nc, std::vector<Outcome>(size_t(reps)));
  std::vector<std::pair<size_t, int>> pending;
  for (size_t c = 0; c < nc; ++c)
    if (use[c])
      for (int r = 0; r < reps; ++r) pending.push_back({c, r});
  parallel_each(pending.size(), threads_, [&](size_t k) {
    auto [c, r] = pending[k];
    results[c][size_t(r)] = simulate(c, extension, params, first + r);
  });
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
