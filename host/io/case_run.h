// `repose run`: a case simulated into its output folder, safe to interrupt and to continue.
// - The folder belongs to this run (io/output_dir.h: locked against every other process while it
//   runs); every path and the restart state are checked before the first step.
// - Frames, wall forces, the .pvd series and summary.json are written as the run goes
//   (io/run_output.h); summary.json says "running", "finished" or "interrupted".
// - `[output] checkpoint_interval` writes checkpoint.state every so many simulated seconds.
// - SIGINT/SIGTERM stop at the next batch: files flushed, summary and checkpoint written,
//   exit code 128 + signal.
// - `restart` continues from a state file to the same bytes as a run that never stopped; into
//   the folder of the same run (same case hash) it keeps the frames up to the state's step.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "case/case_spec.h"
#include "engine/backend.h"

namespace repose {

struct CaseRunOptions {
  std::string backend = kUserBackend;  // auto: a hardware GPU, else cpu (resolve_backend)
  int device = -1;
  unsigned threads = 0;                // cpu backend; 0: every core
  std::string variant;                 // kernel variant; empty: the backend's fastest
  std::optional<uint64_t> steps;       // run this many steps (more, with restart) ...
  std::optional<double> time;          // ... or this much simulated time; else to end_time
  std::string out_dir;                 // empty: out/NAME
  bool overwrite = false;              // empty a non-empty out_dir first
  std::string state_out;               // the final state, when given
  std::string restart;                 // a state file to continue from
  std::vector<std::string> overrides;  // --set KEY=VALUE as given (for the provenance)
  bool quiet = false;
  bool wall_impulses = false;          // wall_forces.csv also gives each wall's peak and impulse per row
};

// Returns the exit code: 0 when the run finished, 128 + the signal when one stopped it. Throws
// BadInput (OutputError for an unusable or busy folder, InputError for a restart state that is
// damaged, changed, inconsistent or of another case) before anything is written; a failure during
// the run (WriteError: a full disk) ends summary.json as "failed: REASON" and is rethrown.
// The case is taken by value: its particles are let go once the model holds them.
int run_case_to_folder(CaseSpec spec, const CaseRunOptions& options);

}  // namespace repose
