#include "io/frame_recorder.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace repose {

double default_frame_interval(const Model& model, double max_time) {
  // Bytes of one frame: per sphere its particle arrays (~90 B) and ~3 contact lines (~28 B each).
  double frame_bytes = 200.0 * model.n_particles + 4096;
  return std::max(0.01, max_time * frame_bytes / 5e8);
}

FrameRecorder::FrameRecorder(FrameRequest request, const Model& model)
    : request_(std::move(request)), bounds_(drawing_bounds(model)), labels_(particle_labels(model)),
      walls_(!model.walls.empty()) {
  std::filesystem::create_directories(request_.dir + "/frames");
}

std::string FrameRecorder::file(const char* kind, size_t index) const {
  char tail[32];
  std::snprintf(tail, sizeof tail, "%s%05zu.vtp", kind, index);
  return "frames/" + request_.name + "_" + tail;
}

void FrameRecorder::observe(Simulation& sim) {
  // Half a step of slack: a batch that ends on the due time writes its frame.
  if (sim.time() + 0.5 * sim.model().dt < next_) return;
  size_t k = times_.size();
  const std::string& dir = request_.dir;
  write_vtk_frame(dir + "/" + file("", k), sim.state(), sim.time(), labels_);
  write_contact_frame(dir + "/" + file("contacts_", k), sim.state(),
                      touching_pairs(sim.state(), sim.contact_forces(), labels_), sim.time());
  if (walls_) write_wall_frame(dir + "/" + file("walls_", k), sim.model(), sim.time(), bounds_);
  times_.push_back(sim.time());
  while (next_ <= sim.time() + 0.5 * sim.model().dt) next_ += request_.interval;
  write_series();
}

void FrameRecorder::write_series() const {
  std::vector<SeriesEntry> particles, contacts, walls;
  for (size_t k = 0; k < times_.size(); ++k) {
    particles.push_back({times_[k], file("", k)});
    contacts.push_back({times_[k], file("contacts_", k)});
    if (walls_) walls.push_back({times_[k], file("walls_", k)});
  }
  const std::string stem = request_.dir + "/" + request_.name;
  write_pvd(stem + ".pvd", particles);
  write_pvd(stem + "_contacts.pvd", contacts);
  if (walls_) write_pvd(stem + "_walls.pvd", walls);
}

void record_frames(Simulation& sim, const FrameRequest& request) {
  if (!request.wanted()) return;
  auto recorder = std::make_shared<FrameRecorder>(request, sim.model());
  recorder->observe(sim);
  sim.set_observer([recorder](Simulation& s) { recorder->observe(s); });
}

}  // namespace repose
