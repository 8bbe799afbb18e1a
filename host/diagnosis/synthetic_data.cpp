#include "diagnosis/synthetic_data.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <filesystem>
#include <random>
#include <sstream>
#include <stdexcept>

#include "case/case_loader.h"
#include "case/particle_factory.h"
#include "experiments/repose.h"
#include "diagnosis/diagnosed_experiments.h"
#include "diagnosis/extensions.h"
#include "diagnosis/heap_bed.h"
#include "diagnosis/heap_fill.h"
#include "diagnosis/heap_measures.h"
#include "diagnosis/impact_phase.h"
#include "experiments/drop.h"
#include "experiments/roll.h"
#include "experiments/tilt.h"
#include "util/atomic_file.h"

namespace repose {

namespace {

// Standard normal deviates from a seeded 64-bit generator (Box-Muller on 53-bit uniforms), the
// same numbers on every platform.
class Gaussian {
 public:
  explicit Gaussian(uint64_t seed) : rng_(seed) {}
  double operator()() {
    double u1 = ((rng_() >> 11) + 0.5) * 0x1.0p-53, u2 = (rng_() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
  }

 private:
  std::mt19937_64 rng_;
};

std::string text(double v) {
  std::ostringstream s;
  s.precision(7);
  s << v;
  return s.str();
}

// The case column: the case's path relative to the CSV's folder.
std::string case_column_of(const SyntheticTruth& truth, const std::string& csv_path) {
  namespace fs = std::filesystem;
  return fs::relative(fs::absolute(truth.case_path), fs::absolute(csv_path).parent_path()).generic_string();
}

// A file whose conditions vary one key and whose rows are scalars (heap, slide, roll).
class ScalarRows {
 public:
  ScalarRows(const SyntheticTruth& truth, const std::string& condition_key, const std::string& csv_path)
      : case_column_(case_column_of(truth, csv_path)), sigma_(truth.write_sigma) {
    csv_ << "case,set:" << condition_key << ",measure,value,replicate" << (sigma_ ? ",sigma" : "") << "\n";
  }
  void add(const std::string& condition, const std::string& measure, double value, int replicate, double sd) {
    csv_ << case_column_ << "," << condition << "," << measure << "," << text(value) << "," << replicate
         << (sigma_ ? "," + text(sd) : "") << "\n";
  }
  std::string str() const { return csv_.str(); }

 private:
  std::string case_column_;
  bool sigma_;
  std::ostringstream csv_;
};

// The heap measures a truth asks for, checked; default repose_angle and bed_height.
std::vector<std::string> heap_measures_of(const SyntheticTruth& truth) {
  if (truth.bed_height_only) return {"bed_height"};
  if (truth.heap_measures.empty()) return {"repose_angle", "bed_height"};
  for (const std::string& m : truth.heap_measures)
    if (std::find(heap_measure_names().begin(), heap_measure_names().end(), m) == heap_measure_names().end()) {
      std::string names;
      for (const auto& n : heap_measure_names()) names += (names.empty() ? "" : ", ") + n;
      throw std::runtime_error("'" + m + "' is not a heap measure (" + names + ")");
    }
  return truth.heap_measures;
}

void write_heap_data(const SyntheticTruth& truth, const std::string& condition_key, const ModelExtension* ext,
                     const std::string& csv_path) {
  std::vector<std::string> measures = heap_measures_of(truth);
  Gaussian noise(truth.seed);
  ScalarRows rows(truth, condition_key, csv_path);
  for (size_t ci = 0; ci < truth.heights.size(); ++ci) {
    std::string value = text(truth.heights[ci]);
    for (int rep = 1; rep <= truth.replicates; ++rep) {
      CaseSpec spec = load_case(truth.case_path, {{condition_key, value}});
      if (truth.grain_friction) heap_interaction(spec).static_friction = *truth.grain_friction;
      if (ext) ext->apply(spec, truth.extension_params);
      spec.spheres.clear();
      for (FillSpec& f : spec.fills) f.seed = 1000000 + 10000 * truth.seed + 100 * ci + uint64_t(rep);
      fill_heap(spec);  // as the diagnosis fills (heap_fill.h)
      std::map<std::string, double> heap;
      if (truth.bed_height_only) heap["bed_height"] = measure_bed_height(spec);
      else heap = heap_measures(run_repose(spec, {}, true), spec.experiment.heap_side);  // a lone spinning grain
                                                                                         // does not change the heap
      for (const std::string& m : measures) {
        double sd = m == "repose_angle" ? truth.angle_noise : m == "profile_convexity" ? truth.convexity_noise : truth.noise;
        rows.add(value, m, heap.at(m) + sd * noise(), rep, sd);
      }
    }
  }
  write_file_atomically(csv_path, rows.str());
}

// One body tilted or rolled per condition (deterministic), its replicates the measurement noise.
void write_tilt_or_roll_data(const SyntheticTruth& truth, const std::string& condition_key,
                             const ModelExtension* ext, const std::string& csv_path) {
  Gaussian noise(truth.seed);
  ScalarRows rows(truth, condition_key, csv_path);
  for (double condition : truth.heights) {
    std::string value = text(condition);
    CaseSpec spec = load_case(truth.case_path, {{condition_key, value}});
    const DiagnosedExperiment* kind = diagnosed_experiment(spec);
    if (truth.plate_friction) kind->baseline_value(spec) = *truth.plate_friction;
    if (ext) ext->apply(spec, truth.extension_params);
    std::string measure = kind->measures.front();
    double simulated = 0, sd = truth.angle_noise;
    if (kind->id == "roll") {
      simulated = run_roll(spec).rolling_distance;
      sd = truth.noise;
    } else {
      simulated = run_tilt(spec).onset_angle_deg;
    }
    for (int rep = 1; rep <= truth.replicates; ++rep) rows.add(value, measure, simulated + sd * noise(), rep, sd);
  }
  write_file_atomically(csv_path, rows.str());
}

}  // namespace

void write_synthetic_data(const SyntheticTruth& truth, const std::string& csv_path) {
  const ModelExtension* ext = nullptr;
  if (!truth.extension.empty()) {
    ext = find_extension(truth.extension);
    if (!ext || !ext->apply) throw std::runtime_error("no simulated extension '" + truth.extension + "'");
    if (truth.extension_params.size() != ext->parameters.size())
      throw std::runtime_error(truth.extension + " takes " + std::to_string(ext->parameters.size()) + " parameter(s)");
  }
  if (truth.heights.empty()) throw std::runtime_error("synthetic data needs at least one condition (drop height)");
  CaseSpec plain = load_case(truth.case_path);
  const DiagnosedExperiment* kind = diagnosed_experiment(plain);
  if (!kind) throw std::runtime_error(truth.case_path + ": diagnose does not simulate experiment '" +
                                      plain.experiment.type + "'");
  std::string key = truth.condition_key.empty() ? kind->condition : truth.condition_key;
  if (kind->id == "repose") {
    write_heap_data(truth, key, ext, csv_path);
    return;
  }
  if (kind->id != "drop") {
    write_tilt_or_roll_data(truth, key, ext, csv_path);
    return;
  }
  std::string case_column = case_column_of(truth, csv_path);
  Gaussian noise(truth.seed);
  std::ostringstream csv;
  // A drop varies its height (the impact alignment and the trajectories are written around it).
  csv << "case,set:" << kind->condition << ",measure,value,replicate,t" << (truth.write_sigma ? ",sigma" : "") << "\n";
  csv.precision(7);
  auto sigma = [&](double sd) {
    std::ostringstream s;
    s.precision(7);
    if (truth.write_sigma) s << "," << sd;
    return s.str();
  };
  for (size_t hi = 0; hi < truth.heights.size(); ++hi) {
    double h = truth.heights[hi];
    std::ostringstream hs;
    hs << h;
    CaseSpec spec = load_case(truth.case_path, {{kind->condition, hs.str()}});
    if (truth.restitution) body_plate_interaction(spec).restitution = *truth.restitution;
    if (ext) ext->apply(spec, truth.extension_params);
    align_impact_phase(spec);  // as the diagnosis simulates (impact_phase.h)
    bool stochastic = !spec.bodies.empty();
    std::vector<DropResult> drops;
    for (int rep = 1; rep <= (stochastic ? truth.replicates : 1); ++rep) {
      if (stochastic) spec.seed = 1000000 + 10000 * truth.seed + 100 * hi + uint64_t(rep);
      drops.push_back(run_drop(spec));
    }
    auto drop_of = [&](int rep) -> const DropResult& { return drops[stochastic ? size_t(rep - 1) : 0]; };
    for (int rep = 1; rep <= truth.replicates; ++rep)
      csv << case_column << "," << hs.str() << ",rebound_height," << drop_of(rep).rebound_height + truth.noise * noise()
          << "," << rep << "," << sigma(truth.noise) << "\n";
    if (truth.series_dt > 0) {
      // The camera's frames, linear between simulated frames, up to the rebound apex.
      for (int rep = 1; rep <= truth.replicates; ++rep) {
        const auto& tr = drop_of(rep).trajectory;
        size_t k = 1;
        double rho = truth.series_correlation, error = 0;
        for (int i = 0; i * truth.series_dt <= tr.back().first; ++i) {
          error = i == 0 ? noise() : rho * error + std::sqrt(1 - rho * rho) * noise();
          double t = i * truth.series_dt;
          while (k + 1 < tr.size() && tr[k].first < t) ++k;
          double w = (t - tr[k - 1].first) / (tr[k].first - tr[k - 1].first);
          double z = tr[k - 1].second + w * (tr[k].second - tr[k - 1].second);
          csv << case_column << "," << hs.str() << ",height," << z + truth.series_noise * error << "," << rep << ","
              << t << sigma(truth.series_noise) << "\n";
        }
      }
    }
  }
  write_file_atomically(csv_path, csv.str());
}

}  // namespace repose
