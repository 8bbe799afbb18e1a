// The files of one `repose run` in its output folder, written as the run goes so that an
// interrupted run leaves everything up to its last frame readable:
// - frames/NAME_00000.vtp (particles), frames/NAME_contacts_00000.vtp (the force network) and
//   frames/NAME_walls_00000.vtp (walls) every output interval, listed with their times in
//   NAME.pvd, NAME_contacts.pvd and NAME_walls.pvd (ParaView's time series), each written whole
//   or not at all (util/atomic_file.h);
// - wall_forces.csv, one row per frame, flushed with every row (a failed write throws WriteError
//   with the system's reason);
// - checkpoint.state, the latest restartable state (docs/state-format.md).
// Frame k is the state after k * frame_every steps; a continued run keeps frames 0 .. k of the
// step it continues from and rewrites what came after (the same bytes: runs are deterministic).
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "engine/simulation.h"
#include "io/vtk_writer.h"
#include "util/file_output.h"

namespace repose {

class RunOutput {
 public:
  // frame_every: steps between frames (0: none); vtk: write VTK frames (else only wall forces);
  // case_hash: recorded in checkpoints (io/state_file.h).
  // impulses: wall_forces.csv also has each wall's peak and impulse since the previous row (the
  // simulation sums them: Simulation::sum_wall_forces).
  RunOutput(std::string dir, std::string name, std::string case_hash, const Model& model, uint64_t frame_every, bool vtk,
            bool impulses = false);

  // Starts the files for a run that begins at `step` (0: a new run). With `continuing`, the
  // folder holds the same run up to at least `step`: frames and wall-force rows after `step`
  // are removed and the rest kept; otherwise the folder is empty.
  void begin(uint64_t step, bool continuing);
  // Called after every step a frame falls on (and at step 0): frame files and a wall-force row.
  // Throws WriteError when a file cannot be written.
  void frame(Simulation& sim);
  bool frame_due(uint64_t step) const { return frame_every_ && step % frame_every_ == 0; }
  // Rewrites the .pvd series to list every frame so far (at checkpoints and at the end).
  void write_series() const;
  std::string checkpoint_path() const { return dir_ + "/checkpoint.state"; }
  void checkpoint(const Simulation& sim) const;
  unsigned frames_written() const { return frames_written_; }
  const std::string& dir() const { return dir_; }
  const std::string& name() const { return name_; }
  const std::string& case_hash() const { return case_hash_; }

 private:
  std::string frame_file(const char* kind, uint64_t index) const;
  void keep_wall_force_rows(uint64_t rows);
  void remove_frames_from(uint64_t index) const;

  std::string dir_, name_, case_hash_;
  const Model& model_;
  uint64_t frame_every_;
  bool vtk_;
  bool walls_;
  bool impulses_;
  Bounds bounds_;
  ParticleLabels labels_;
  uint64_t first_frame_ = 0, next_frame_ = 0;
  unsigned frames_written_ = 0;
  std::unique_ptr<FileOutput> wall_csv_;
};

}  // namespace repose
