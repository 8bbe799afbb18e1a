// Watching an experiment: `repose experiment --frames` writes the VTK frames `repose run` writes
// (particles with orientation and material, walls, the contact force network), each a valid file
// ParaView reads (header, appended blocks), every one listed in its .pvd; the force network has one
// line per touching pair of spheres.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "case/case_loader.h"
#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "io/vtk_writer.h"
#include "tests/cli_support.h"
#include "tests/vtk_checks.h"

namespace fs = std::filesystem;
using namespace repose;

namespace {

// The frames/ files whose name starts with `prefix` and continues with digits.
std::vector<std::string> frame_files(const fs::path& dir, const std::string& prefix) {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir / "frames")) {
    std::string f = e.path().filename().string();
    if (f.rfind(prefix, 0) == 0 && std::isdigit((unsigned char)f[prefix.size()])) files.push_back("frames/" + f);
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST_CASE("repose experiment --frames writes valid VTK frames, each listed in its .pvd", "[experiments][frames]") {
  fs::path out = fs::temp_directory_path() / "repose_test_experiment_frames";
  fs::remove_all(out);
  auto run = test::run_repose("experiment drop " + std::string(REPOSE_SOURCE_DIR) +
                              "/cases/drop_cabbage.toml --quiet --threads 1 --frames 0.02 --out " + out.string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  auto drop = nlohmann::json::parse(std::ifstream(out / "drop.json"));
  for (const std::string kind : {"", "contacts_", "walls_"}) {
    std::string stem = "drop_cabbage" + std::string(kind.empty() ? "" : "_" + kind.substr(0, kind.size() - 1));
    std::vector<std::string> listed = test::pvd_files(out / (stem + ".pvd"));
    INFO(stem << ".pvd");
    CHECK(listed == frame_files(out, "drop_cabbage_" + kind));
    // A frame every 0.02 s from release to the rebound's apex (the camera samples every 1 ms).
    double end = drop["contact_time"].get<double>() + std::sqrt(2 * 0.5 / 9.81) + 0.01;
    CHECK(listed.size() >= size_t(end / 0.02));
    for (const auto& f : listed) {
      if (kind == "") test::check_vtp(out / f, {"radius", "body_id", "material", "orientation", "velocity"});
      if (kind == "walls_") test::check_vtp(out / f, {"wall_index"});
      if (kind == "contacts_") test::check_vtp(out / f, {"normal_force", "force"});
    }
  }
  fs::remove_all(out);
}

TEST_CASE("the contact force network has one line per touching pair of spheres", "[experiments][frames]") {
  // 1200 spheres poured into the box from up to 0.3 m, after 0.5 s: a bed three spheres deep.
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml", {{"fill.0.count", "1200"}});
  Model model = build_model(spec);
  Simulation sim(model, make_backend("cpu", -1, 1, gpu::kDefaultWorkgroup));
  sim.advance(uint64_t(0.5 / model.dt));
  const HostState& s = sim.state();
  ParticleLabels labels = particle_labels(sim.model());
  std::vector<ContactLine> lines = touching_pairs(s, sim.contact_forces(), labels);
  // Every pair whose surfaces overlap, by brute force over all pairs.
  std::vector<std::pair<uint32_t, uint32_t>> touching, drawn;
  for (uint32_t i = 0; i < s.pos.size(); ++i)
    for (uint32_t j = i + 1; j < s.pos.size(); ++j) {
      double dx = double(s.pos[i].x) - s.pos[j].x, dy = double(s.pos[i].y) - s.pos[j].y,
             dz = double(s.pos[i].z) - s.pos[j].z;
      if (std::sqrt(dx * dx + dy * dy + dz * dz) < double(s.pos[i].w) + double(s.pos[j].w)) touching.push_back({i, j});
    }
  for (const auto& l : lines) drawn.push_back({l.i, l.j});
  std::sort(drawn.begin(), drawn.end());
  CHECK(touching.size() > 1200);  // a bed: more than one contact per sphere
  CHECK(drawn == touching);
  // Touching spheres push each other apart; EDEM's damping (normal_attraction = "allow") may pull
  // for a moment at the end of a contact, so nearly all, not all, are repulsive in a settling bed.
  size_t repulsive = 0;
  for (const auto& l : lines) repulsive += l.normal_force > 0;
  CHECK(repulsive > 0.95 * lines.size());
  fs::path file = fs::temp_directory_path() / "repose_test_contacts.vtp";
  write_contact_frame(file.string(), s, lines, sim.time());
  CHECK(test::check_vtp(file, {"normal_force", "force"}) == touching.size());
  fs::remove(file);
}
