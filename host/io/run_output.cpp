#include "io/run_output.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "io/csv_columns.h"
#include "io/state_file.h"
#include "util/atomic_file.h"

namespace repose {

namespace fs = std::filesystem;

RunOutput::RunOutput(std::string dir, std::string name, std::string case_hash, const Model& model, uint64_t frame_every,
                     bool vtk, bool impulses)
    : dir_(std::move(dir)), name_(std::move(name)), case_hash_(std::move(case_hash)), model_(model), frame_every_(frame_every),
      vtk_(vtk && frame_every > 0), walls_(!model.walls.empty()), impulses_(impulses), bounds_(drawing_bounds(model)),
      labels_(particle_labels(model)) {}

std::string RunOutput::frame_file(const char* kind, uint64_t index) const {
  char file[64];
  std::snprintf(file, sizeof file, "%s%05llu.vtp", kind, (unsigned long long)index);
  return "frames/" + name_ + "_" + file;
}

void RunOutput::begin(uint64_t step, bool continuing) {
  // Frames 0 .. step / frame_every were written before `step`; the next one follows.
  next_frame_ = frame_every_ ? (step == 0 && !continuing ? 0 : step / frame_every_ + 1) : 0;
  first_frame_ = continuing ? 0 : next_frame_;
  if (vtk_) fs::create_directories(dir_ + "/frames");
  if (continuing) remove_frames_from(next_frame_);
  if (!walls_) return;
  std::string csv = dir_ + "/wall_forces.csv";
  if (continuing && fs::exists(csv)) {
    keep_wall_force_rows(next_frame_);
    wall_csv_ = std::make_unique<FileOutput>(csv, FileOutput::Mode::Append);
    return;
  }
  wall_csv_ = std::make_unique<FileOutput>(csv, FileOutput::Mode::Truncate);
  std::ostream& out = wall_csv_->stream();
  out << wall_force_csv_header(model_.wall_group_names(), impulses_) << "\n";
  wall_csv_->flush();
}

void RunOutput::remove_frames_from(uint64_t index) const {
  if (!fs::is_directory(dir_ + "/frames")) return;
  std::vector<fs::path> later;
  for (const auto& entry : fs::directory_iterator(dir_ + "/frames")) {
    std::string file = entry.path().filename().string();
    if (file.rfind(name_ + "_", 0) != 0 || entry.path().extension() != ".vtp") continue;
    std::string stem = entry.path().stem().string();
    size_t digits = stem.find_last_not_of("0123456789") + 1;
    if (digits < stem.size() && std::stoull(stem.substr(digits)) >= index) later.push_back(entry.path());
  }
  for (const auto& p : later) fs::remove(p);
}

// Keeps the header and the first `rows` rows (the frames before the continued step).
void RunOutput::keep_wall_force_rows(uint64_t rows) {
  std::ifstream in(dir_ + "/wall_forces.csv");
  std::string line, kept;
  for (uint64_t k = 0; k <= rows && std::getline(in, line); ++k) kept += line + "\n";
  in.close();
  write_file_atomically(dir_ + "/wall_forces.csv", kept);
}

void RunOutput::frame(Simulation& sim) {
  uint64_t index = frame_every_ ? sim.step() / frame_every_ : 0;
  next_frame_ = index + 1;
  ++frames_written_;
  if (vtk_) {
    write_vtk_frame(dir_ + "/" + frame_file("", index), sim.state(), sim.time(), labels_);
    write_contact_frame(dir_ + "/" + frame_file("contacts_", index), sim.state(),
                        touching_pairs(sim.state(), sim.contact_forces(), labels_), sim.time());
    if (walls_) write_wall_frame(dir_ + "/" + frame_file("walls_", index), model_, sim.time(), bounds_);
  }
  if (wall_csv_) {
    std::ostream& out = wall_csv_->stream();
    out << wall_force_csv_row(sim.time(), sim.wall_forces(),
                              impulses_ ? sim.take_wall_impulses() : std::vector<WallImpulse>{})
        << "\n";
    wall_csv_->flush();  // a killed run keeps every row up to its last frame
  }
}

void RunOutput::write_series() const {
  if (!vtk_) return;
  std::vector<SeriesEntry> particles, contacts, walls;
  for (uint64_t k = first_frame_; k < next_frame_; ++k) {
    double t = double(k * frame_every_) * model_.dt;
    if (fs::exists(dir_ + "/" + frame_file("", k))) particles.push_back({t, frame_file("", k)});
    if (fs::exists(dir_ + "/" + frame_file("contacts_", k))) contacts.push_back({t, frame_file("contacts_", k)});
    if (walls_ && fs::exists(dir_ + "/" + frame_file("walls_", k))) walls.push_back({t, frame_file("walls_", k)});
  }
  write_pvd(dir_ + "/" + name_ + ".pvd", particles);
  write_pvd(dir_ + "/" + name_ + "_contacts.pvd", contacts);
  if (walls_) write_pvd(dir_ + "/" + name_ + "_walls.pvd", walls);
}

void RunOutput::checkpoint(const Simulation& sim) const {
  write_state_file(checkpoint_path(), sim.state(), sim.step(), sim.time(), case_hash_);
  write_series();
}

}  // namespace repose
