// repose: deterministic DEM on Vulkan compute. Dispatches `repose VERB ...` to its verb.
// Exit codes (README, "Exit codes"; cli/cli_checks.h): 0 done, 1 a failure while working, 2 bad
// input of any kind, 3 a calibration that missed its target, 128 + N stopped by signal N.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "cli/cli_checks.h"
#include "cli/verbs.h"
#include "experiments/registry.h"

int main(int argc, char** argv) {
  using namespace repose::cli;
  repose::install_experiments();  // the case loader reads [experiment] through them
  std::vector<Verb> verbs;
  for (auto group : {engine_verbs, bench_verbs, experiment_verbs, stats_verbs, optimize_verbs, geometry_verbs, calibrate_verbs,
                     diagnose_verbs})
    for (auto& v : group()) verbs.push_back(std::move(v));

  auto usage = [&](FILE* out) {
    std::fprintf(out, "usage: repose VERB [options]   (repose VERB --help for its options)\n\nverbs:\n");
    for (const auto& v : verbs) std::fprintf(out, "  %-14s %s\n", v.name.c_str(), v.summary.c_str());
  };
  if (argc < 2) { usage(stderr); return 2; }
  if (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    usage(stdout);
    return 0;
  }
  for (const auto& v : verbs) {
    if (v.name != argv[1]) continue;
    std::string prog = std::string("repose ") + argv[1];
    std::vector<char*> args(argv + 1, argv + argc);
    args[0] = prog.data();
    try {
      return v.run(static_cast<int>(args.size()), args.data());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "repose %s: error: %s\n", argv[1], e.what());
      return failure_exit_code(e);
    }
  }
  std::fprintf(stderr, "repose: unknown verb '%s'\n\n", argv[1]);
  usage(stderr);
  return 2;
}
