// VTK frames of a simulation an experiment drives (`repose experiment --frames`), the same files
// as `repose run` writes (io/vtk_writer.h): frames/NAME_00000.vtp (particles),
// NAME_contacts_00000.vtp (the force network), NAME_walls_00000.vtp, and their series NAME.pvd,
// NAME_contacts.pvd, NAME_walls.pvd, rewritten with every frame so that a run that fails or is
// killed leaves a series ParaView opens. An experiment advances in samples of its own, so a frame
// is written at the first batch end at or after each interval (its true time is in the .pvd).
#pragma once
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "io/vtk_writer.h"

namespace repose {

struct FrameRequest {
  std::string dir;     // the output folder (frames/ goes inside); empty: no frames
  std::string name;    // file stem: the case's name, a replicate's suffix
  double interval = 0; // simulated seconds between frames
  bool wanted() const { return !dir.empty() && interval > 0; }
};

// The default interval of `repose experiment --frames`: 0.01 s (100 frames per simulated second),
// or less often so that frames up to max_time stay under about 500 MB.
double default_frame_interval(const Model& model, double max_time);

class FrameRecorder {
 public:
  FrameRecorder(FrameRequest request, const Model& model);
  // Writes a frame when one is due (and the first one at once).
  void observe(Simulation& sim);
  unsigned frames() const { return unsigned(times_.size()); }

 private:
  std::string file(const char* kind, size_t index) const;
  void write_series() const;
  FrameRequest request_;
  Bounds bounds_;
  ParticleLabels labels_;
  bool walls_;
  double next_ = 0;
  std::vector<double> times_;
};

// Attaches a recorder to `sim` (Simulation::set_observer) when the request wants frames, and
// writes the first frame now.
void record_frames(Simulation& sim, const FrameRequest& request);

}  // namespace repose
