// `repose run` as a long job: its output folder is its own, its paths are checked before the
// first step, it continues from a state or checkpoint to the bytes of a run that never stopped,
// and SIGINT/SIGTERM stop it cleanly (files flushed, summary and checkpoint written, exit 128+sig).
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "tests/cli_support.h"
#include "tests/vtk_checks.h"

namespace fs = std::filesystem;
using repose::test::fresh_dir;
using repose::test::run_repose;
using repose::test::slurp;

namespace {

const std::string kBox = std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml";
// The settling box with a frame every ~21 steps, on the cpu backend.
const std::string kRun = "run " + kBox + " --backend cpu --quiet --set output.interval=0.002";

// Every file under `dir` (relative name -> bytes), summary.json left out (it records timings).
std::map<std::string, std::string> files_of(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "summary.json" && e.path().extension() != ".state")
      files[fs::relative(e.path(), dir).string()] = slurp(e.path());
  return files;
}

}  // namespace

TEST_CASE("run: a non-empty --out is refused, --overwrite empties it, run and experiment default apart",
          "[engine][cli][output]") {
  fs::path dir = fresh_dir("out_folder");
  auto first = run_repose(kRun + " --steps 20 --out " + (dir / "o").string());
  REQUIRE(first.status == 0);
  std::ofstream(dir / "o" / "frames" / "settle_box_00099.vtp") << "an older, longer run's frame";
  auto again = run_repose(kRun + " --steps 20 --out " + (dir / "o").string());
  INFO(again.output);
  CHECK(again.status == 2);
  CHECK(again.output.find("is not empty") != std::string::npos);
  CHECK(again.output.find("--overwrite") != std::string::npos);
  CHECK(fs::exists(dir / "o" / "frames" / "settle_box_00099.vtp"));  // nothing touched
  auto over = run_repose(kRun + " --steps 20 --overwrite --out " + (dir / "o").string());
  CHECK(over.status == 0);
  CHECK_FALSE(fs::exists(dir / "o" / "frames" / "settle_box_00099.vtp"));
  CHECK(fs::exists(dir / "o" / "frames" / "settle_box_00000.vtp"));
  // --overwrite never deletes the case the run reads.
  fs::copy_file(kBox, dir / "o" / "box.toml");
  auto own = run_repose("run " + (dir / "o" / "box.toml").string() + " --backend cpu --steps 1 --overwrite --out " +
                        (dir / "o").string());
  CHECK(own.status == 2);
  CHECK(own.output.find("which this run reads") != std::string::npos);
  CHECK(fs::exists(dir / "o" / "box.toml"));

  // Default folders: out/NAME for run, out/experiment/NAME for experiment (checked by the
  // folder each refuses when it is taken).
  fs::create_directories(dir / "cwd" / "out" / "settle_box");
  std::ofstream(dir / "cwd" / "out" / "settle_box" / "x") << "taken";
  auto run_default = run_repose(kRun + " --steps 1", (dir / "cwd").string());
  CHECK(run_default.status == 2);
  CHECK(run_default.output.find("out/settle_box is not empty") != std::string::npos);
  fs::create_directories(dir / "cwd" / "out" / "experiment" / "drop_sphere");
  std::ofstream(dir / "cwd" / "out" / "experiment" / "drop_sphere" / "x") << "taken";
  auto experiment_default = run_repose(std::string("experiment drop ") + REPOSE_SOURCE_DIR + "/cases/drop_sphere.toml",
                                       (dir / "cwd").string());
  CHECK(experiment_default.status == 2);
  CHECK(experiment_default.output.find("out/experiment/drop_sphere is not empty") != std::string::npos);
}

TEST_CASE("run: output paths are checked before the first step", "[engine][cli][output]") {
  fs::path dir = fresh_dir("out_paths");
  auto missing = run_repose(kRun + " --steps 50 --out " + (dir / "o").string() + " --state-out " +
                            (dir / "no_such_folder" / "final.state").string());
  INFO(missing.output);
  CHECK(missing.status == 2);
  CHECK(missing.output.find("no_such_folder") != std::string::npos);
  CHECK(missing.output.find("steps 0 to") == std::string::npos);  // no step was taken
  CHECK_FALSE(fs::exists(dir / "o"));
  std::ofstream(dir / "file") << "x";
  auto file = run_repose(kRun + " --steps 50 --out " + (dir / "file").string());
  CHECK(file.status == 2);
  CHECK(file.output.find("is a file, not a folder") != std::string::npos);
}

TEST_CASE("run --restart continues to the same bytes, frames and wall forces as a run that never stopped",
          "[engine][cli][restart]") {
  fs::path dir = fresh_dir("cli_restart");
  fs::path whole = dir / "whole", split = dir / "split";
  REQUIRE(run_repose(kRun + " --steps 300 --out " + whole.string() + " --state-out " + (dir / "whole.state").string()).status == 0);
  REQUIRE(run_repose(kRun + " --steps 130 --out " + split.string() + " --state-out " + (dir / "at130.state").string()).status == 0);
  // Continued in its own folder (the same case and --set), on lavapipe from the cpu's state.
  auto resumed = run_repose("run " + kBox + " --backend vulkan --quiet --set output.interval=0.002 --steps 170 --restart " +
                            (dir / "at130.state").string() + " --out " + split.string() + " --state-out " +
                            (dir / "resumed.state").string());
  INFO(resumed.output);
  REQUIRE(resumed.status == 0);
  CHECK(slurp(dir / "whole.state") == slurp(dir / "resumed.state"));
  auto a = files_of(whole), b = files_of(split);
  CHECK(a.size() == b.size());
  for (const auto& [name, bytes] : a) {
    INFO(name);
    CHECK((b.count(name) && b[name] == bytes));
  }
  auto summary = nlohmann::json::parse(slurp(split / "summary.json"));
  CHECK(summary["restarted_from"]["step"] == 130);
  CHECK(summary["steps"] == 300);
  // Another case's state is not continued from, and another case's folder not continued into.
  auto other = run_repose(kRun + " --set simulation.seed=2 --steps 10 --restart " + (dir / "at130.state").string() +
                          " --out " + split.string());
  CHECK(other.status == 2);
  CHECK(other.output.find("at130.state: written by a run of case ") != std::string::npos);
  CHECK(other.output.find(", not of this case (") != std::string::npos);
  REQUIRE(run_repose(kRun + " --set simulation.seed=2 --steps 10 --out " + (dir / "seed2").string()).status == 0);
  auto into = run_repose(kRun + " --steps 10 --restart " + (dir / "at130.state").string() + " --out " + (dir / "seed2").string());
  CHECK(into.status == 2);
  CHECK(into.output.find("another case (or other --set values)") != std::string::npos);
}

// The device stores particles in cell order (host/engine/particle_order.h); whether and how often
// it reorders them changes no byte a user sees: frames, wall frames, CSV, state file.
TEST_CASE("run: the particles' storage order changes no byte of any output, spheres and clumps",
          "[engine][cli][order]") {
  fs::path dir = fresh_dir("cli_order");
  const std::string clumps = "run " + std::string(REPOSE_SOURCE_DIR) +
                             "/cases/cabbage_settle.toml --backend cpu --quiet --set output.interval=0.004";
  for (const std::string& run : {kRun, clumps}) {
    std::map<std::string, std::string> reference;
    std::string reference_state;
    for (const char* variant : {"reorder=0", "reorder=1", "reorder=5"}) {
      fs::path out = dir / variant;
      fs::remove_all(out);
      auto r = run_repose(run + " --steps 300 --variant " + variant + " --out " + out.string() + " --state-out " +
                          (dir / "order.state").string() + " --overwrite");
      INFO(run << " --variant " << variant << ": " << r.output);
      REQUIRE(r.status == 0);
      auto files = files_of(out);
      std::string state = slurp(dir / "order.state");
      if (reference.empty()) {
        reference = files;
        reference_state = state;
        CHECK(reference.size() > 5);
        continue;
      }
      CHECK(state == reference_state);
      CHECK(files.size() == reference.size());
      for (const auto& [name, bytes] : reference) {
        INFO(name);
        CHECK((files.count(name) && files[name] == bytes));
      }
    }
  }
}

TEST_CASE("run: VTK frames, wall frames and .pvd series ParaView can read, provenance in summary.json",
          "[engine][cli][output]") {
  fs::path dir = fresh_dir("vtk_series");
  auto r = run_repose(std::string("run ") + REPOSE_SOURCE_DIR + "/cases/drop_cabbage.toml --backend cpu --quiet --steps 40 "
                      "--set output.interval=1e-4 --set simulation.seed=5 --out " + (dir / "o").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  auto summary = nlohmann::json::parse(slurp(dir / "o" / "summary.json"));
  std::string name = summary["case"].get<std::string>();
  name = fs::path(name).stem().string();
  std::string pvd = slurp(dir / "o" / (name + ".pvd")), walls_pvd = slurp(dir / "o" / (name + "_walls.pvd"));
  size_t frames = summary["frames"];
  CHECK(frames >= 5);
  auto count = [](const std::string& s) {
    size_t n = 0;
    for (size_t at = s.find("<DataSet"); at != std::string::npos; at = s.find("<DataSet", at + 1)) ++n;
    return n;
  };
  CHECK(count(pvd) == frames);
  CHECK(count(walls_pvd) == frames);
  CHECK(count(slurp(dir / "o" / (name + "_contacts.pvd"))) == frames);
  repose::test::check_vtp(dir / "o" / "frames" / (name + "_00001.vtp"),
                          {"radius", "speed", "id", "body_id", "material", "orientation", "velocity",
                           "angular_velocity", "force"});
  repose::test::check_vtp(dir / "o" / "frames" / (name + "_walls_00001.vtp"), {"wall_index"});
  repose::test::check_vtp(dir / "o" / "frames" / (name + "_contacts_00001.vtp"), {"normal_force", "force"});
  // 203 sub-spheres of one cabbage: one body id.
  const auto& p = summary["provenance"];
  CHECK(!p["version"].get<std::string>().empty());
  CHECK(p["case_hash"].get<std::string>().size() == 16);
  CHECK(p["overrides"] == nlohmann::json::array({"output.interval=1e-4", "simulation.seed=5"}));
  CHECK(p["seed"] == 5);
  CHECK(p["backend"] == "cpu");
  CHECK(p["device"].get<std::string>().find("thread") != std::string::npos);
}

TEST_CASE("run: SIGTERM and SIGINT stop cleanly, the checkpoint continues to the bytes of a whole run",
          "[engine][cli][restart]") {
  for (int signal : {SIGTERM, SIGINT}) {
    fs::path dir = fresh_dir("signal");
    fs::path out = dir / "o";
    pid_t pid = repose::test::spawn_repose(
        {"run", kBox, "--backend", "cpu", "--threads", "1", "--steps", "100000", "--set", "output.interval=0.002",
         "--set", "output.checkpoint_interval=0.01", "--out", out.string()},
        (dir / "log").string());
    // Wait for a few frames, then stop it.
    for (int k = 0; k < 600; ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      std::ifstream rows(out / "wall_forces.csv");
      if (std::count(std::istreambuf_iterator<char>(rows), {}, '\n') > 8) break;
    }
    kill(pid, signal);
    int status = 0;
    waitpid(pid, &status, 0);
    INFO(slurp(dir / "log"));
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 128 + signal);
    auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
    CHECK(summary["status"] == (signal == SIGINT ? "interrupted by SIGINT" : "interrupted by SIGTERM"));
    uint64_t stopped = summary["steps"];
    CHECK(stopped < 100000);
    // Every frame's wall-force row is on disk, and the series lists every frame.
    std::ifstream rows(out / "wall_forces.csv");
    size_t lines = std::count(std::istreambuf_iterator<char>(rows), {}, '\n');
    CHECK(lines == 1 + size_t(summary["frames"]));
    CHECK(fs::exists(out / "settle_box.pvd"));
    REQUIRE(fs::exists(out / "checkpoint.state"));
    if (signal == SIGINT) continue;  // one comparison with a whole run is enough
    auto rest = run_repose(kRun + " --set output.checkpoint_interval=0.01 --steps 30 --restart " +
                           (out / "checkpoint.state").string() + " --out " + out.string() + " --state-out " +
                           (dir / "resumed.state").string());
    REQUIRE(rest.status == 0);
    auto whole = run_repose(kRun + " --set output.checkpoint_interval=0.01 --steps " + std::to_string(stopped + 30) +
                            " --out " + (dir / "whole").string() + " --state-out " + (dir / "whole.state").string());
    REQUIRE(whole.status == 0);
    CHECK(slurp(dir / "whole.state") == slurp(dir / "resumed.state"));
    CHECK(slurp(dir / "whole" / "wall_forces.csv") == slurp(out / "wall_forces.csv"));
  }
}
