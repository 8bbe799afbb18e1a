// How an experiment runs (not what it measures): backend, threads, progress on stderr, frames.
#pragma once
#include <string>

#include "engine/backend.h"
#include "io/frame_recorder.h"

namespace repose {

struct ExperimentRunOptions {
  std::string backend = kLibraryBackend;
  int device = -1;
  unsigned threads = 1;
  bool progress = false;  // progress with ETA on stderr (host/util/progress.h)
  bool profile = false;   // time every kernel (results carry per-phase profiles either way)
  FrameRequest frames;    // VTK frames as the experiment goes (`repose experiment --frames`)
  bool wall_impulses = false;  // wall_forces.csv: each wall's peak and impulse between samples
  // A resumable experiment (Experiment::resumable(), experiments/experiment_checkpoint.h) writes
  // its checkpoints into checkpoint_dir (empty: none, and signals are not its business) and
  // continues from the checkpoint state `restart` (empty: from the start).
  std::string checkpoint_dir;
  std::string restart;
};

}  // namespace repose
