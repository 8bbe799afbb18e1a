// The command-line verbs of `repose`, grouped by the part of the program that owns them.
// Each group lives in its own file of host/cli/ and returns its verbs; main.cpp lists the groups.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace repose::cli {

struct Verb {
  std::string name;                          // e.g. "run", "design"
  std::string summary;                       // one line for `repose --help`
  std::function<int(int argc, char** argv)>  // argv[0] is "repose <name>"
      run;
};

std::vector<Verb> engine_verbs();    // verbs_engine.cpp: devices, run
std::vector<Verb> bench_verbs();     // verbs_bench.cpp: bench
std::vector<Verb> stats_verbs();     // verbs_stats.cpp: design, fit, curve
std::vector<Verb> optimize_verbs();  // verbs_optimize.cpp: optimize
std::vector<Verb> geometry_verbs();  // verbs_geometry.cpp: clump, stl, heap-angle
std::vector<Verb> experiment_verbs();  // verbs_experiments.cpp: experiment
std::vector<Verb> calibrate_verbs();   // verbs_calibrate.cpp: calibrate
std::vector<Verb> diagnose_verbs();    // verbs_diagnose.cpp: diagnose, synth-data, extensions

}  // namespace repose::cli
