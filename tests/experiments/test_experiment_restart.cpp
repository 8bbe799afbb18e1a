// `repose experiment repose` stops on SIGINT/SIGTERM with a checkpoint, and `--restart` continues
// it to the files of an experiment that never stopped; a checkpoint that does not belong is
// refused (experiments/experiment_checkpoint.h).
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <thread>

#include "../cli_support.h"

namespace fs = std::filesystem;

namespace {

const std::string kBucket = std::string(REPOSE_SOURCE_DIR) + "/cases/experiments/repose_bucket_spheres.toml";
// The bucket rig (454 spheres) with a fast gate, as test_repose.cpp runs it, a checkpoint every 0.1 s.
const std::vector<std::string> kSets = {"--set", "wall.gate.motion.start=1.0", "--set", "wall.gate.motion.stop=2.8",
                                        "--set", "wall.gate.motion.velocity=[0.0,0.0,0.25]", "--set",
                                        "experiment.lift_end=2.8", "--set", "experiment.max_time=10", "--set",
                                        "output.checkpoint_interval=0.1"};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string joined(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += " " + w;
  return s;
}

fs::path fresh_dir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("repose_test_experiment_restart_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The experiment in `out`, stopped by `signal` once a checkpoint at `seconds` or later has been
// written (each replaces checkpoint.json); returns its exit status. The run lasts at least 2.8 s.
int stopped_experiment(const fs::path& out, const fs::path& log, int signal, double seconds) {
  std::vector<std::string> args = {"experiment", "repose", kBucket, "--backend", "cpu", "--threads", "1", "--quiet",
                                   "--out", out.string()};
  args.insert(args.end(), kSets.begin(), kSets.end());
  pid_t pid = repose::test::spawn_repose(args, log.string());
  for (int k = 0; k < 6000; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    auto j = nlohmann::json::parse(slurp(out / "checkpoint.json"), nullptr, false);
    if (j.is_object() && j.value("time_s", 0.0) >= seconds - 1e-9) break;
  }
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The restart of the experiment whose checkpoint is in `out`: its result files are those of the
// unbroken run in `whole`, byte for byte, and repose.json the same but for its provenance and
// wall-clock times. Returns the restart's repose.json.
nlohmann::json restarted_as_whole(const fs::path& out, const fs::path& whole) {
  auto rest = repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet" +
                                       joined(kSets) + " --restart " + (out / "checkpoint.state").string());
  INFO(rest.output);
  REQUIRE(rest.status == 0);
  for (const char* file : {"energy.csv", "heap.csv", "wall_forces.csv", "heap.png"}) {
    INFO(file);
    CHECK(slurp(whole / file) == slurp(out / file));
  }
  auto a = nlohmann::json::parse(slurp(whole / "repose.json"));
  auto b = nlohmann::json::parse(slurp(out / "repose.json"));
  const nlohmann::json restarted = b;
  for (auto* j : {&a, &b}) {  // what may differ: the wall-clock times and where it restarted from
    j->erase("provenance");
    for (auto& phase : (*j)["phases"]) phase.erase("wall_s");
  }
  CHECK(a.dump() == b.dump());
  return restarted;
}

}  // namespace

TEST_CASE("repose experiment: stopped by a signal and restarted, the same result files as a whole run",
          "[experiments][cli][restart]") {
  fs::path dir = fresh_dir("whole");
  auto whole = repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet --out " +
                                        (dir / "whole").string() + joined(kSets));
  INFO(whole.output);
  REQUIRE(whole.status == 0);
  // Stopped in the fill (at the first checkpoint, 0.1 s; the bed is measured at 1 s) and in the lift (1.5 s).
  for (auto [signal, seconds] : {std::pair{SIGINT, 0.1}, std::pair{SIGTERM, 1.5}}) {
    fs::path out = dir / ("cut" + std::to_string(signal));
    int code = stopped_experiment(out, dir / "log", signal, seconds);
    INFO(slurp(dir / "log"));
    REQUIRE(code == 128 + signal);
    CHECK(slurp(dir / "log").find("continue with --restart") != std::string::npos);
    CHECK(!fs::exists(out / "repose.json"));  // no result until the experiment ends
    nlohmann::json restarted = restarted_as_whole(out, dir / "whole");
    CHECK(restarted["provenance"]["restarted_from"] == (out / "checkpoint.state").string());
  }
}

// --profile counts the checkpoints and their time, which the phases' times leave out: one at
// every 0.1 s reached by a sample before the last (the last sample ends the run instead).
TEST_CASE("repose experiment --profile: the checkpoints written and their time", "[experiments][cli][restart]") {
  fs::path dir = fresh_dir("profile");
  auto run = repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet --profile --out " +
                                      (dir / "out").string() + joined(kSets));
  INFO(run.output);
  REQUIRE(run.status == 0);
  double settle = nlohmann::json::parse(slurp(dir / "out" / "repose.json"))["settle_time"].get<double>();
  int expected = 0;
  while ((expected + 1) * 0.1 < settle - 0.025) ++expected;  // samples every 0.05 s
  REQUIRE(expected > 10);
  std::string line = "checkpoints (outside the phases): " + std::to_string(expected) + " written in ";
  size_t at = run.output.find(line);
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(run.output.substr(at + line.size())) > 0);  // seconds
}

// A heap still moving at its max_time is measured as it stood (exit 1); --max-time, outside the
// case's identity, lets its last checkpoint go on to the result of a run given more time.
TEST_CASE("repose experiment --max-time: a heap not settled by then goes on from its checkpoint to the result of a "
          "run with more time", "[experiments][cli][restart]") {
  fs::path dir = fresh_dir("longer");
  auto whole = repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet --out " +
                                        (dir / "whole").string() + joined(kSets));
  INFO(whole.output);
  REQUIRE(whole.status == 0);
  fs::path out = dir / "short";
  auto cut = repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet --out " +
                                      out.string() + joined(kSets) + " --max-time 3");
  INFO(cut.output);
  REQUIRE(cut.status == 1);
  auto measured_early = nlohmann::json::parse(slurp(out / "repose.json"));
  CHECK(measured_early["status"] == "failed");
  CHECK(measured_early["reason"].get<std::string>().find("had not settled") != std::string::npos);
  CHECK(measured_early["provenance"]["max_time"] == 3.0);
  CHECK(restarted_as_whole(out, dir / "whole")["provenance"]["max_time"] == 10.0);  // the case's
}

// Too little time for the lift is the user's to fix: exit 2, the flag or key named, no result.
TEST_CASE("repose experiment: a max_time before the lift ends is bad input, with the flag or key named",
          "[experiments][cli]") {
  fs::path dir = fresh_dir("short_max_time");
  auto flag = repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet --out " +
                                       (dir / "flag").string() + joined(kSets) + " --max-time 2.5");
  INFO(flag.output);
  CHECK(flag.status == 2);
  CHECK(flag.output.find("--max-time: 2.5 s must exceed the end of the lift (2.8 s)") != std::string::npos);
  CHECK(!fs::exists(dir / "flag"));  // checked before the folder is claimed
  auto key = repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet --out " +
                                      (dir / "key").string() + joined(kSets) + " --set experiment.max_time=2");
  INFO(key.output);
  CHECK(key.status == 2);
  CHECK(key.output.find("max_time: 2 s must exceed the end of the lift (2.8 s)") != std::string::npos);
  CHECK(!fs::exists(dir / "key"));
}

TEST_CASE("repose experiment --restart refuses what does not belong, with exit code 2 and nothing written",
          "[experiments][cli][restart]") {
  fs::path dir = fresh_dir("refused");
  fs::path out = dir / "cut";
  REQUIRE(stopped_experiment(out, dir / "log", SIGINT, 0.1) == 128 + SIGINT);
  const std::string state = (out / "checkpoint.state").string();
  auto restart = [&](const std::string& extra) {
    return repose::test::run_repose("experiment repose " + kBucket + " --backend cpu --threads 1 --quiet" +
                                    joined(kSets) + " --restart " + state + extra);
  };
  auto other_case = restart(" --set simulation.seed=9");
  CHECK(other_case.status == 2);
  CHECK(other_case.output.find("not of this case") != std::string::npos);
  auto elsewhere = restart(" --out " + (dir / "elsewhere").string());
  CHECK(elsewhere.status == 2);
  CHECK(elsewhere.output.find("folder of its checkpoint") != std::string::npos);
  auto overwrite = restart(" --overwrite");
  CHECK(overwrite.status == 2);
  auto drop = repose::test::run_repose("experiment drop " + std::string(REPOSE_SOURCE_DIR) +
                                       "/cases/drop_sphere.toml --quiet --restart " + state);
  CHECK(drop.status == 2);
  CHECK(drop.output.find("--restart applies to repose") != std::string::npos);
  // The progress and the state of different steps (a stop between their two writes).
  auto j = nlohmann::json::parse(slurp(out / "checkpoint.json"));
  j["step"] = j["step"].get<uint64_t>() + 1;
  std::ofstream(out / "checkpoint.json") << j.dump();
  auto mismatched = restart("");
  CHECK(mismatched.status == 2);
  CHECK(mismatched.output.find("not written together") != std::string::npos);
  fs::remove(out / "checkpoint.json");
  auto missing = restart("");
  CHECK(missing.status == 2);
  CHECK(missing.output.find("checkpoint.json") != std::string::npos);
  CHECK(!fs::exists(out / "repose.json"));
}
