// How an experiment runs (not what it measures): backend, threads, progress on stderr.
#pragma once
#include <string>

#include "engine/backend.h"

namespace repose {

struct ExperimentRunOptions {
  std::string backend = kLibraryBackend;
  int device = -1;
  unsigned threads = 1;
  bool progress = false;  // progress with ETA on stderr (host/util/progress.h)
  bool profile = false;   // time every kernel (results carry per-phase profiles either way)
};

}  // namespace repose
