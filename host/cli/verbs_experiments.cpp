// `repose experiment TYPE CASE.toml`: the studies' lab tests as simulations, measured like the lab.
// The experiment the case names (experiments/registry.h) runs it, prints what it measured and
// writes TYPE.json with the files it declares (time series as CSV, wall forces, a heap's picture).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "cli/cli_case.h"
#include "cli/verbs.h"
#include "experiments/registry.h"

namespace repose::cli {

namespace {

std::string listed(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& w : words) text += (text.empty() ? "" : ", ") + w;
  return text;
}

int run_experiment(int argc, char** argv) {
  std::string descriptions;
  for (const Experiment* e : experiments()) descriptions += (descriptions.empty() ? "" : ", ") + e->description();
  CLI::App app{"Run a virtual experiment: " + descriptions + "."};
  std::string type, case_path, backend = "cpu", out_dir;
  unsigned threads = 1;
  int device = -1;
  std::vector<std::string> sets;
  double height = -1;
  bool quiet = false;
  app.add_option("type", type, "experiment: " + listed(experiment_types()))
      ->required()
      ->check(CLI::IsMember(experiment_types()));
  app.add_option("case", case_path, "case file (TOML) with an [experiment] table")->required();
  app.add_option("--height", height, "drop: height H of the lowest point (m); default from the case");
  app.add_option("--backend", backend, "cpu (default) or vulkan")->check(CLI::IsMember({"vulkan", "cpu"}));
  app.add_option("--threads", threads, "cpu backend threads (default 1)");
  app.add_option("--device", device, "Vulkan device index");
  app.add_option("--set", sets, "override a case key: KEY=VALUE (repeatable)");
  app.add_option("--out", out_dir, "output folder (default out/CASE_NAME)");
  app.add_flag("--quiet", quiet, "no progress output");
  int replicates = 1;
  app.add_option("--replicates", replicates,
                 "drop: N drops with seeds seed, seed+1, ... (a clump lands at a random orientation each)")
      ->check(CLI::Range(1, 1000));
  CLI11_PARSE(app, argc, argv);

  std::vector<CaseOverride> extra;
  if (height > 0) extra.push_back({"experiment.drop_height", std::to_string(height)});
  auto loaded = load_case_or_report(case_path, sets, extra);
  if (!loaded) return 2;
  CaseSpec& spec = *loaded;
  const Experiment* experiment = experiment_for(spec);
  if (spec.experiment.type != type || !experiment) {
    std::fprintf(stderr, "%s: [experiment] type is '%s', not '%s'\n", case_path.c_str(),
                 spec.experiment.type.c_str(), type.c_str());
    return 2;
  }
  if (out_dir.empty()) out_dir = "out/" + spec.name;
  ExperimentRun run;
  run.backend = backend;
  run.device = device;
  run.threads = threads;
  run.progress = !quiet;
  run.replicates = replicates;
  try {
    std::filesystem::create_directories(out_dir);
    ExperimentOutcome outcome = experiment->run(spec, run);
    for (const std::string& line : write_outcome(measured_or_throw(outcome), type + ".json", out_dir))
      std::printf("%s\n", line.c_str());
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

std::vector<Verb> experiment_verbs() {
  return {{"experiment", "virtual lab test: " + listed(experiment_types()) + " (prints the result, writes JSON + CSV)",
           run_experiment}};
}

}  // namespace repose::cli
