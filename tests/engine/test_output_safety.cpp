// Files a user can trust: a folder another run is writing is refused and the refusal names that
// run; a write that fails (a fault injected at the Nth write, or a real full filesystem where the
// test can mount one) ends the run with the system's reason, a summary that says "failed: ..."
// and only whole files; a restart removes what a killed writer left half-written.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sys/mount.h>
#include <thread>

#include "plot/chart.h"
#include "tests/cli_support.h"
#include "util/atomic_file.h"
#include "util/file_output.h"

namespace fs = std::filesystem;
using repose::test::fresh_dir;
using repose::test::run_repose;
using repose::test::slurp;

namespace {

const std::string kBox = std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml";
const std::string kRun = "run " + kBox + " --backend cpu --threads 1 --quiet --set output.interval=0.002";

// `repose ARGS` with REPOSE_FAIL_WRITE=n: its nth write to the system fails with ENOSPC.
repose::test::CliRun run_failing_at(int n, const std::string& args) {
  ::setenv("REPOSE_FAIL_WRITE", std::to_string(n).c_str(), 1);
  auto r = run_repose(args);
  ::unsetenv("REPOSE_FAIL_WRITE");
  return r;
}

// What a failed run must leave: no temporary, every frame whole (a VTK file ends with its closing
// tag), every wall-force row complete, and a summary that ends the run as failed, with the reason.
void check_failed_run_folder(const fs::path& out) {
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    std::string name = e.path().filename().string();
    INFO(e.path());
    CHECK(name.find(".tmp.") == std::string::npos);
    CHECK(name != ".repose.lock");
    if (e.path().extension() == ".vtp" || e.path().extension() == ".pvd") {
      std::string text = slurp(e.path());
      CHECK(text.size() > 12);
      CHECK(text.substr(text.size() - 11) == "</VTKFile>\n");
    }
  }
  if (fs::exists(out / "wall_forces.csv")) {
    std::ifstream rows(out / "wall_forces.csv");
    std::string header, row;
    std::getline(rows, header);
    while (std::getline(rows, row)) CHECK(std::count(row.begin(), row.end(), ',') == std::count(header.begin(), header.end(), ','));
  }
  REQUIRE(fs::exists(out / "summary.json"));
  std::string status = nlohmann::json::parse(slurp(out / "summary.json"))["status"];
  CHECK(status.rfind("failed: ", 0) == 0);
  CHECK(status.find("No space left on device") != std::string::npos);
}

}  // namespace

TEST_CASE("two runs into one folder: the second is refused and names the first", "[engine][cli][output]") {
  fs::path dir = fresh_dir("two_runs"), out = dir / "o";
  pid_t first = repose::test::spawn_repose({"run", kBox, "--backend", "cpu", "--threads", "1", "--steps", "100000", "--out",
                                            out.string(), "--set", "output.interval=0.002"},
                                           (dir / "first.log").string());
  for (int k = 0; k < 600 && !fs::exists(out / "summary.json"); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  auto second = run_repose(kRun + " --steps 20 --out " + out.string());
  auto overwrite = run_repose(kRun + " --steps 20 --overwrite --out " + out.string());
  auto experiment = run_repose(std::string("experiment drop ") + REPOSE_SOURCE_DIR + "/cases/drop_sphere.toml --out " + out.string());
  std::string frames_before = std::to_string(std::distance(fs::directory_iterator(out / "frames"), {}));
  kill(first, SIGTERM);
  int status = 0;
  waitpid(first, &status, 0);
  INFO(slurp(dir / "first.log"));
  for (const auto& r : {second, overwrite, experiment}) {
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK(r.output.find(out.string() + " is in use by process " + std::to_string(first) + " (") != std::string::npos);
    CHECK(r.output.find("repose run " + kBox) != std::string::npos);  // its command line
    CHECK(r.output.find(", since 20") != std::string::npos);           // and when it started
  }
  // The first ran on undisturbed, stopped cleanly, and released the folder.
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 128 + SIGTERM);
  CHECK(nlohmann::json::parse(slurp(out / "summary.json"))["status"] == "interrupted by SIGTERM");
  CHECK_FALSE(fs::exists(out / ".repose.lock"));
  CHECK_FALSE(fs::exists(out / "drop.json"));
  auto after = run_repose(kRun + " --steps 20 --out " + out.string());
  CHECK(after.output.find("is not empty") != std::string::npos);  // now only the usual rule
  fs::remove_all(dir);
}

TEST_CASE("a write that fails half-way: the reason, a failed summary, only whole files", "[engine][cli][output]") {
  fs::path dir = fresh_dir("fail_write");
  // Early, in a frame, in a later frame or row (about 5 writes per frame).
  for (int n : {2, 5, 9, 17, 26}) {
    fs::path out = dir / ("o" + std::to_string(n));
    auto r = run_failing_at(n, kRun + " --steps 120 --set output.checkpoint_interval=0.005 --out " + out.string());
    INFO("failing write " << n << ": " << r.output);
    CHECK(r.status == 1);
    CHECK(r.output.find("No space left on device") != std::string::npos);
    CHECK(r.output.find("cannot write " + out.string()) != std::string::npos);  // names the file
    check_failed_run_folder(out);
  }
  // An experiment whose series cannot be written leaves a failure record, no result (frames off: the series is its first write).
  fs::path out = dir / "drop";
  auto drop = run_failing_at(1, std::string("experiment drop ") + REPOSE_SOURCE_DIR + "/cases/drop_sphere.toml --backend cpu "
                                "--threads 1 --quiet --set output.vtk=false --out " + out.string());
  INFO(drop.output);
  CHECK(drop.status == 1);
  CHECK(drop.output.find("trajectory.csv: No space left on device") != std::string::npos);
  auto record = nlohmann::json::parse(slurp(out / "drop.json"));  // the failure, not a result
  CHECK(record["status"] == "failed");
  CHECK(record["reason"].get<std::string>().find("trajectory.csv: No space left on device") != std::string::npos);
  CHECK_FALSE(record.contains("rebound_height"));
  CHECK_FALSE(fs::exists(out / "trajectory.csv"));
  fs::remove_all(dir);
}

TEST_CASE("a PNG or result file that cannot be written leaves the old one or none, and says why", "[engine][output]") {
  fs::path dir = fresh_dir("fail_png");
  repose::Chart chart(200, 150, 0, 1, 0, 1);
  chart.title("a figure");
  chart.labels("x (m)", "y (m)");
  repose::fail_nth_write(1);
  CHECK_THROWS_WITH(chart.save((dir / "figure.png").string()), Catch::Matchers::Contains("figure.png: No space left on device"));
  CHECK(fs::is_empty(dir));  // neither the picture nor a temporary
  repose::write_file_atomically((dir / "r.json").string(), std::string("{\"old\": true}\n"));
  repose::fail_nth_write(1);
  CHECK_THROWS_AS(repose::write_file_atomically((dir / "r.json").string(), std::string(200000, 'x')), repose::WriteError);
  CHECK(slurp(dir / "r.json") == "{\"old\": true}\n");
  CHECK(std::distance(fs::directory_iterator(dir), {}) == 1);
  fs::remove_all(dir);
}

TEST_CASE("a full filesystem: the run fails with the system's reason and a failed summary", "[engine][cli][output]") {
  fs::path dir = fresh_dir("full_fs");
  // A 2 MiB tmpfs needs root (CAP_SYS_ADMIN); the fault-injection test above covers the rest.
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=2m") != 0) {
    WARN("skipped the full-filesystem part: cannot mount a tmpfs here (" << std::strerror(errno) << ")");
    fs::remove_all(dir);
    return;
  }
  fs::path out = dir / "o";
  auto r = run_repose(kRun + " --steps 400 --out " + out.string());
  INFO(r.output);
  CHECK(r.status == 1);
  CHECK(r.output.find("No space left on device") != std::string::npos);
  check_failed_run_folder(out);
  ::umount(dir.c_str());
  fs::remove_all(dir);
}

TEST_CASE("a restart removes the temporaries a killed writer left", "[engine][cli][restart]") {
  fs::path dir = fresh_dir("leftovers"), out = dir / "o";
  const std::string run = kRun + " --set output.checkpoint_interval=0.002";
  REQUIRE(run_repose(run + " --steps 60 --out " + out.string()).status == 0);
  for (const fs::path& p : {out / "frames" / "settle_box_00004.vtp.tmp.99999", out / "checkpoint.state.tmp.123",
                            out / "summary.json.tmp.7"})
    std::ofstream(p) << "half a file";
  std::ofstream(out / "notes.tmp.txt") << "not ours";
  auto r = run_repose(run + " --steps 20 --restart " + (out / "checkpoint.state").string() + " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    INFO(e.path());
    std::string name = e.path().filename().string();
    CHECK((name.find(".tmp.") == std::string::npos || name == "notes.tmp.txt"));
  }
  fs::remove_all(dir);
}
