#include "diagnosis/synthetic_data.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <stdexcept>

#include "case/case_loader.h"
#include "diagnosis/extensions.h"
#include "experiments/registry.h"
#include "util/progress.h"
#include "util/atomic_file.h"
#include "util/math.h"
#include "util/number_text.h"

namespace repose {

namespace {

// Standard normal deviates from a seeded 64-bit generator (Box-Muller on 53-bit uniforms), the
// same numbers on every platform.
class Gaussian {
 public:
  explicit Gaussian(uint64_t seed) : rng_(seed) {}
  double operator()() {
    double u1 = ((rng_() >> 11) + 0.5) * 0x1.0p-53, u2 = (rng_() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937_64 rng_;
};

std::string text(double v) { return format_g(v, 7); }

// The case column: the case's path relative to the CSV's folder.
std::string case_column_of(const SyntheticTruth& truth, const std::string& csv_path) {
  namespace fs = std::filesystem;
  return fs::relative(fs::absolute(truth.case_path), fs::absolute(csv_path).parent_path()).generic_string();
}

// The rows of the file: case, the condition's value, measure, value, replicate, [t], [sigma].
class Rows {
 public:
  Rows(const SyntheticTruth& truth, const std::string& condition_key, bool series, const std::string& csv_path)
      : case_column_(case_column_of(truth, csv_path)), series_(series), sigma_(truth.write_sigma) {
    csv_ << "case,set:" << condition_key << ",measure,value,replicate" << (series_ ? ",t" : "")
         << (sigma_ ? ",sigma" : "") << "\n";
  }
  void add(const std::string& condition, const std::string& measure, double value, int replicate, double sd,
           const std::string& t = "") {
    csv_ << case_column_ << "," << condition << "," << measure << "," << text(value) << "," << replicate
         << (series_ ? "," + t : "") << (sigma_ ? "," + text(sd) : "") << "\n";
  }
  std::string str() const { return csv_.str(); }

 private:
  std::string case_column_;
  bool series_, sigma_;
  std::ostringstream csv_;
};

// The truth's value of the baseline's free parameter, when given (--restitution, ...).
std::optional<double> truth_baseline(const SyntheticTruth& truth, const DiagnosisRole& role) {
  if (role.truth_option == "restitution") return truth.restitution;
  if (role.truth_option == "grain_friction") return truth.grain_friction;
  if (role.truth_option == "plate_friction") return truth.plate_friction;
  return std::nullopt;
}

// The scalar measures written, in row order (a heap's bed height alone with --bed-only; the
// truth's own list, checked against what the experiment reports).
std::vector<std::string> scalar_measures(const SyntheticTruth& truth, const DiagnosisRole& role) {
  const auto& all = role.synthetic;
  bool has_bed = std::find(all.begin(), all.end(), "bed_height") != all.end();
  if (truth.bed_height_only && has_bed) return {"bed_height"};
  if (truth.measures.empty()) return all;
  for (const std::string& m : truth.measures)
    if (std::none_of(role.measures.begin(), role.measures.end(),
                     [&](const MeasureInfo& i) { return i.name == m && !i.series; })) {
      std::string names;
      for (const auto& i : role.measures)
        if (!i.series) names += (names.empty() ? "" : ", ") + i.name;
      throw std::runtime_error("'" + m + "' is not a scalar measure of this experiment (" + names + ")");
    }
  return truth.measures;
}

// The camera's frames every series_dt, linear between simulated frames, up to the rebound apex,
// with AR(1) noise (a camera's tracking error drifts from frame to frame).
void add_series(Rows& rows, const SyntheticTruth& truth, const std::string& condition, const std::string& measure,
                const std::vector<std::pair<double, double>>& tr, int rep, Gaussian& noise) {
  size_t k = 1;
  double rho = truth.series_correlation, error = 0;
  for (int i = 0; i * truth.series_dt <= tr.back().first; ++i) {
    error = i == 0 ? noise() : rho * error + std::sqrt(1 - rho * rho) * noise();
    double t = i * truth.series_dt;
    while (k + 1 < tr.size() && tr[k].first < t) ++k;
    double w = (t - tr[k - 1].first) / (tr[k].first - tr[k - 1].first);
    double z = tr[k - 1].second + w * (tr[k].second - tr[k - 1].second);
    rows.add(condition, measure, z + truth.series_noise * error, rep, truth.series_noise, text(t));
  }
}

}  // namespace

// Per condition: the truth simulated once (deterministic) or once per replicate (a clump body at
// a random orientation, a refilled heap: seeds 1,000,000 + 10,000 seed + 100 condition index +
// replicate, which no diagnosis uses); per replicate a row of each scalar measure with Gaussian
// noise (SD `angle_noise` for angles, `noise` for lengths, `unitless_noise` for ratios); then, with series_dt, the camera
// track of each replicate.
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
  const Experiment* kind = experiment_for(plain);
  if (!kind || !kind->diagnosis())
    throw std::runtime_error(truth.case_path + ": diagnose does not simulate experiment '" + plain.experiment.type + "'");
  const DiagnosisRole& role = *kind->diagnosis();
  std::string key = truth.condition_key.empty() ? role.condition : truth.condition_key;
  auto series = std::find_if(role.measures.begin(), role.measures.end(), [](const MeasureInfo& m) { return m.series; });
  bool with_series = series != role.measures.end() && truth.series_dt > 0;
  std::vector<std::string> scalars = scalar_measures(truth, role);
  std::vector<std::string> wanted = scalars;
  if (with_series) wanted.push_back(series->name);
  Gaussian noise(truth.seed);
  Rows rows(truth, key, series != role.measures.end(), csv_path);
  int per_condition = kind->stochastic(plain) ? truth.replicates : 1;
  TaskProgress progress("synth-data: simulation", int(truth.heights.size()) * per_condition, truth.progress);
  for (size_t ci = 0; ci < truth.heights.size(); ++ci) {
    std::string value = text(truth.heights[ci]);
    CaseSpec spec = load_case(truth.case_path, {{key, value}});
    if (auto b = truth_baseline(truth, role)) kind->tested_contact(spec).*role.baseline_field = *b;
    if (ext) ext->apply(spec, truth.extension_params);
    kind->prepare_for_diagnosis(spec);
    bool stochastic = kind->stochastic(spec);
    std::vector<DiagnosticOutcome> runs;
    for (int rep = 1; rep <= (stochastic ? truth.replicates : 1); ++rep) {
      CaseSpec replicate = spec;
      if (stochastic) kind->reseed(replicate, 1000000 + 10000 * truth.seed + 100 * ci + uint64_t(rep));
      progress.next(key + " = " + value + (stochastic ? ", replicate " + std::to_string(rep) : ""));
      runs.push_back(kind->simulate_for_diagnosis(replicate, wanted, true));
    }
    auto run_of = [&](int rep) -> const DiagnosticOutcome& { return runs[stochastic ? size_t(rep - 1) : 0]; };
    for (int rep = 1; rep <= truth.replicates; ++rep)
      for (const std::string& m : scalars) {
        const std::string& unit =
            std::find_if(role.measures.begin(), role.measures.end(), [&](const MeasureInfo& i) { return i.name == m; })->unit;
        double sd = unit == "deg" ? truth.angle_noise : unit == "1" ? truth.unitless_noise : truth.noise;
        rows.add(value, m, run_of(rep).values.at(m) + sd * noise(), rep, sd);
      }
    if (with_series)
      for (int rep = 1; rep <= truth.replicates; ++rep)
        add_series(rows, truth, value, series->name, run_of(rep).trajectory, rep, noise);
  }
  write_file_atomically(csv_path, rows.str());
}

}  // namespace repose
