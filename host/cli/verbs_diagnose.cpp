// `repose diagnose DATA.csv`: what the calibrated model still gets wrong, its cause, and the gain
// of the extended model (host/diagnosis/). `repose synth-data CASE.toml`: measured-data CSV
// simulated with a known hidden effect, to check the diagnosis.
#include <CLI/CLI.hpp>
#include <toml++/toml.h>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "case/case_error.h"
#include "cli/cli_checks.h"
#include "cli/verbs.h"
#include "io/output_dir.h"
#include "diagnosis/diagnose.h"
#include "diagnosis/diagnosis_report.h"
#include "diagnosis/extensions.h"
#include "diagnosis/synthetic_data.h"
#include "util/number_text.h"

namespace repose::cli {

namespace {

// --params: a TOML file of case keys, e.g. "interaction.cabbage/steel.restitution" = 0.43 or
// nested tables; each becomes a case override applied to every row's case.
std::vector<CaseOverride> read_params(const std::string& path) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw DataError(path + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
  std::vector<CaseOverride> out;
  std::function<void(const toml::table&, const std::string&)> walk = [&](const toml::table& t, const std::string& prefix) {
    for (auto&& [k, node] : t) {
      std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
      if (node.is_table()) {
        walk(*node.as_table(), key);
      } else if (node.is_number()) {
        out.push_back({key, exact_number(node.is_integer() ? double(node.as_integer()->get())
                                                           : node.as_floating_point()->get())});
      } else if (node.is_string()) {
        out.push_back({key, "\"" + node.as_string()->get() + "\""});
      } else {
        throw DataError(path + ":" + std::to_string(node.source().begin.line) + ": " + key +
                        ": expected a number or a string");
      }
    }
  };
  walk(root, "");
  if (out.empty()) throw DataError(path + ": no parameters in the file");
  return out;
}

int run_diagnose(int argc, char** argv) {
  CLI::App app{"Diagnose a calibrated model against measured data: lack of fit, residual trends, the "
               "candidate extension that explains them, and its held-out gain."};
  std::string data_path, params_path, out_dir, candidates;
  unsigned threads = 2;
  int sim_replicates = 8;
  bool quiet = false;
  app.add_option("data", data_path, "measured data CSV (README, 'Measured data')")->required();
  app.add_option("--params", params_path, "calibrated parameters (TOML of case keys); the baseline is then not refitted");
  app.add_option("--out", out_dir, "folder for diagnosis.json, report.md and figures (default out/diagnose_NAME)")
      ->check(non_empty_path());
  app.add_option("--threads", threads, "simulations run in parallel (default 2)")->check(thread_count());
  app.add_option("--candidates", candidates, "comma-separated extension ids to test (default: all that apply)");
  app.add_option("--sim-replicates", sim_replicates,
                 "simulated replicates per condition for a stochastic model (a clump at random orientations; default 8)")
      ->check(CLI::Range(2, 1000));
  app.add_flag("--quiet", quiet, "no progress lines");
  REPOSE_PARSE(app, argc, argv);
  if (out_dir.empty()) out_dir = "out/diagnose_" + std::filesystem::path(data_path).stem().string();
  try {
    DiagnoseOptions options;
    options.threads = threads;
    options.simulated_replicates = sim_replicates;
    options.progress = !quiet;
    if (!params_path.empty()) {
      options.given = read_params(params_path);
      options.fit_baseline = false;
    }
    std::stringstream list(candidates);
    for (std::string id; std::getline(list, id, ',');)
      if (!id.empty()) options.candidates.push_back(id);
    Observations obs = group_observations(read_measured_data(data_path));
    OutputFolder folder(out_dir);  // ours alone until the diagnosis is written
    folder.remove_leftovers();
    Diagnosis d = diagnose(obs, options);
    write_diagnosis(obs, d, out_dir);
    std::printf("verdict: %s", d.verdict.c_str());
    for (size_t k = 0; k < d.cause.size(); ++k) std::printf("%s%s", k ? ", " : " (", d.cause[k].c_str());
    std::printf("%s\n", d.cause.empty() ? "" : ")");
    for (const auto& s : d.statements) std::printf("  %s\n", s.c_str());
    std::printf("wrote %s/diagnosis.json and %s/report.md (%zu simulations, %.1f s)\n", out_dir.c_str(),
                out_dir.c_str(), d.simulations, d.seconds);
  } catch (const DataError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const CaseError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "diagnose: %s\n", e.what());
    return failure_exit_code(e);
  }
  return 0;
}

int run_synth_data(int argc, char** argv) {
  CLI::App app{"Simulate measured data with a known (hidden) model extension and replicate noise."};
  SyntheticTruth truth;
  std::string out, extension;
  double restitution = -1, grain_friction = -1, plate_friction = -1;
  app.add_option("case", truth.case_path, "drop, heap, slide or roll case (TOML)")->required();
  app.add_option("--extension", extension, "hidden effect ID=VALUE[,VALUE] (e.g. air_drag=0.8); none by default");
  app.add_option("--restitution", restitution, "body-plate restitution of the truth (default: the case's)")->check(finite_between(1e-6, 1));
  app.add_option("--heights", truth.heights, "drop heights, m; for a heap, slide or roll case the values of --condition")
      ->delimiter(',')
      ->required();
  app.add_option("--condition", truth.condition_key,
                 "heap, slide or roll case: the key the conditions vary (default fill.0.count, "
                 "experiment.slope_distance, material.0.density)");
  app.add_option("--grain-friction", grain_friction, "heap case: the grains' sliding friction of the truth")->check(finite_between(0, 10));
  app.add_option("--plate-friction", plate_friction,
                 "slide case: the body-plate sliding friction of the truth; roll case: its rolling friction")->check(finite_between(0, 10));
  app.add_option("--angle-noise", truth.angle_noise, "heap, slide, tilt-roll case: SD of one measured angle, deg (default 0.5)")->check(finite_between(0, 45));
  app.add_flag("--bed-only", truth.bed_height_only, "heap case: bed heights only (the bed alone is simulated, no lift)");
  app.add_option("--measures", truth.measures,
                 "the scalar measures written, comma-separated (a heap's: repose_angle, bed_height, heap_height, "
                 "runout, profile_convexity; default the experiment's usual ones: a heap's repose_angle,bed_height)")
      ->delimiter(',');
  app.add_option("--unitless-noise", truth.unitless_noise,
                 "SD of one measured dimensionless value such as profile_convexity (default 0.01)")
      ->check(finite_between(0, 10));
  app.add_option("--replicates", truth.replicates, "replicates per height (default 5)")->check(whole_number(1, 10000));
  app.add_option("--noise", truth.noise, "SD of one measured length (rebound height, bed height, roll distance), m (default 0.001)")->check(finite_between(0, 10));
  app.add_option("--series-dt", truth.series_dt, "also the trajectory every DT s (default: none)")->check(finite_positive());
  app.add_option("--series-noise", truth.series_noise, "SD of one tracked height, m (default 0.001)")->check(finite_between(0, 10));
  app.add_option("--series-correlation", truth.series_correlation,
                 "lag-1 correlation of a track's noise from frame to frame, AR(1) (default 0: independent)")
      ->check(CLI::Range(0.0, 0.99));
  app.add_option("--seed", truth.seed, "noise seed, and a clump body's orientations (default 1)");
  app.add_flag("--sigma", truth.write_sigma, "write a sigma column (the noise SDs): diagnose then scores the replicate scatter too");
  bool quiet = false;
  app.add_flag("--quiet", quiet, "no progress lines");
  app.add_option("--out", out, "CSV to write")->check(non_empty_path())->required();
  REPOSE_PARSE(app, argc, argv);
  truth.progress = !quiet;
  try {
    if (restitution > 0) truth.restitution = restitution;
    if (grain_friction > 0) truth.grain_friction = grain_friction;
    if (plate_friction > 0) truth.plate_friction = plate_friction;
    if (!extension.empty()) {
      auto eq = extension.find('=');
      if (eq == std::string::npos) throw std::runtime_error("--extension: write ID=VALUE");
      truth.extension = extension.substr(0, eq);
      std::stringstream values(extension.substr(eq + 1));
      for (std::string v; std::getline(values, v, ',');) truth.extension_params.push_back(std::stod(v));
    }
    write_synthetic_data(truth, out);
    std::printf("wrote %s\n", out.c_str());
  } catch (const CaseError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "synth-data: %s\n", e.what());
    return 2;
  }
  return 0;
}

// The candidate extensions as their rows declare them (diagnosis/extensions.cpp).
int run_extensions(int argc, char** argv) {
  CLI::App app{"List the candidate model extensions diagnose tests: parameters, ranges, revealing measures, "
               "case keys and where their physics lives."};
  REPOSE_PARSE(app, argc, argv);
  for (const ModelExtension& e : model_extensions()) {
    std::printf("%s\n  %s\n", e.id.c_str(), e.description.c_str());
    for (const FreeParameter& p : e.parameters)
      std::printf("  parameter   %s (%s) %s to %s%s\n", p.name.c_str(), p.unit.c_str(), format_g(p.lo).c_str(),
                  format_g(p.hi).c_str(), p.log_scale ? ", searched in log" : "");
    std::string measures;
    for (const auto& m : e.revealed_by) measures += (measures.empty() ? "" : ", ") + m;
    std::printf("  revealed by %s%s\n", measures.empty() ? e.pending_reason.c_str() : measures.c_str(),
                e.needs_sigma ? " (replicate scatter: data with sigma)" : "");
    std::printf("  case keys   %s\n  physics     %s\n", e.case_keys.c_str(), e.physics.c_str());
  }
  return 0;
}

}  // namespace

std::vector<Verb> diagnose_verbs() {
  return {{"diagnose", "what a calibrated model gets wrong against measured data, and why", run_diagnose},
          {"synth-data", "measured-data CSV simulated with a hidden model extension", run_synth_data},
          {"extensions", "the candidate model extensions: parameters, ranges, revealing measures, case keys", run_extensions}};
}

}  // namespace repose::cli
