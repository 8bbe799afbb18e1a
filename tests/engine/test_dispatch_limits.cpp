// What a hardware GPU does differently, exercised on lavapipe. Some GPUs allow only 65,535
// workgroups along x: larger dispatches run in rows along y (gpu::dispatch_rows), and
// REPOSE_MAX_GROUPS_X lowers that limit so that small cases run the split paths. GPUs round / and
// sqrt their own way: the kernels correct that (div_rn, sqrt_rn), and REPOSE_ROUNDING=test first
// puts lavapipe's results up to 2 ULP off so that the correction runs here. A large case's scans
// take their block passes over the whole device; REPOSE_SCAN_BLOCKS_FROM=1 makes small ones do so.
// A discrete GPU's memory is reached through staging buffers of at most 64 MiB, in pieces;
// REPOSE_STAGING=N sends lavapipe's transfers that way, in pieces of N bytes (N/2 in turn through
// two halves when a transfer is larger). Either way a settling box and a clump settle give the cpu backend's state bytes.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "tests/cli_support.h"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// The state after `steps` steps of `case_file` on `backend`, with at most `max_x` groups per row
// (0: default) and `env` ("NAME=value ") in the environment.
std::string state_after(const std::string& case_file, const std::string& backend, int steps, int max_x,
                        const fs::path& dir, const std::string& extra_env = "") {
  std::string tag = case_file.substr(0, case_file.find('.')) + "_" + backend + "_" + std::to_string(max_x) +
                    (extra_env.empty() ? "" : "_env");
  fs::path out = dir / tag, state = dir / (tag + ".state");
  std::string env = (max_x ? "REPOSE_MAX_GROUPS_X=" + std::to_string(max_x) + " " : "") + extra_env;
  auto r = repose::test::run_repose_env(env, "run " + std::string(REPOSE_SOURCE_DIR) + "/cases/" + case_file +
                                                 " --backend " + backend + " --steps " + std::to_string(steps) +
                                                 " --quiet --out " + out.string() + " --state-out " + state.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  return slurp(state);
}

// `name`=`value` in the environment: a run refused with a message naming `name`.
void check_refused(const std::string& name, const std::string& value, const std::string& backend = "cpu") {
  auto r = repose::test::run_repose_env(name + "=" + value + " ",
                                        "run " + std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml --backend " +
                                            backend + " --steps 1 --quiet --overwrite --out " +
                                            (fs::temp_directory_path() / "repose_test_env_bad").string());
  INFO(name << "=" << value << ": " << r.output);
  CHECK(r.status != 0);
  CHECK(r.output.find(name) != std::string::npos);
}

// The settling box (200 steps) and the cabbage settle (60 steps) on lavapipe with `env`
// ("NAME=value ") in the environment: the cpu backend's state bytes.
void check_cpu_bytes_on_lavapipe_with(const std::string& env, const fs::path& dir) {
  std::string whole = state_after("settle_box.toml", "cpu", 200, 0, dir);
  CHECK(state_after("settle_box.toml", "vulkan", 200, 0, dir, env) == whole);
  std::string clumps = state_after("cabbage_settle.toml", "cpu", 60, 0, dir);
  CHECK(state_after("cabbage_settle.toml", "vulkan", 60, 0, dir, env) == clumps);
}

}  // namespace

TEST_CASE("dispatches split into rows of workgroups give the same bytes on both backends", "[engine][bitexact]") {
  fs::path dir = fs::temp_directory_path() / "repose_test_dispatch_rows";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // 2,400 spheres: 38 groups of 64 per particle dispatch; 3 per row makes 13 rows.
  std::string whole = state_after("settle_box.toml", "cpu", 120, 0, dir);
  CHECK(whole.size() > 100000);
  CHECK(state_after("settle_box.toml", "cpu", 120, 3, dir) == whole);
  CHECK(state_after("settle_box.toml", "vulkan", 120, 3, dir) == whole);
  CHECK(state_after("settle_box.toml", "vulkan", 120, 1, dir) == whole);
  // The scans in their block passes (REPOSE_SCAN_BLOCKS_FROM=1): 2 blocks of rows, 5 of buckets,
  // in rows of 3 and of 1 workgroup.
  CHECK(state_after("settle_box.toml", "vulkan", 120, 3, dir, "REPOSE_SCAN_BLOCKS_FROM=1 ") == whole);
  CHECK(state_after("settle_box.toml", "vulkan", 120, 1, dir, "REPOSE_SCAN_BLOCKS_FROM=1 ") == whole);
  CHECK(state_after("settle_box.toml", "cpu", 120, 0, dir, "REPOSE_SCAN_BLOCKS_FROM=1 ") == whole);
  // Clumps add body kernels and a contact list over sub-spheres; 5 walls go through rows of 2.
  std::string clumps = state_after("cabbage_settle.toml", "cpu", 40, 0, dir);
  CHECK(state_after("cabbage_settle.toml", "vulkan", 40, 2, dir) == clumps);
  CHECK(state_after("cabbage_settle.toml", "vulkan", 40, 2, dir, "REPOSE_SCAN_BLOCKS_FROM=1 ") == clumps);
}

TEST_CASE("REPOSE_MAX_GROUPS_X outside 1 ... 65535 is refused by name", "[engine]") {
  check_refused("REPOSE_MAX_GROUPS_X", "70000");
}

TEST_CASE("REPOSE_SCAN_BLOCKS_FROM that is not a whole number from 1 is refused by name", "[engine]") {
  for (const char* bad : {"0", "-1", "8x", "99999999999"}) check_refused("REPOSE_SCAN_BLOCKS_FROM", bad);
}

TEST_CASE("divisions and square roots put 2 ULP off and corrected give the cpu backend's bytes", "[engine][bitexact]") {
  fs::path dir = fs::temp_directory_path() / "repose_test_rounding";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // Clumps normalise their quaternions (a square root and four divisions per body and step).
  check_cpu_bytes_on_lavapipe_with("REPOSE_ROUNDING=test ", dir);
  check_refused("REPOSE_ROUNDING", "fast", "vulkan");
}

TEST_CASE("transfers through small staging buffers, in pieces, give the same bytes", "[engine][bitexact]") {
  fs::path dir = fs::temp_directory_path() / "repose_test_staging";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // 4,099 bytes: every buffer of the settling box (2,400 spheres, 38 kB per vec4 row) goes in
  // several pieces, cut inside its elements; the uploads of a reorder and the state read back for
  // the state file go the same way.
  check_cpu_bytes_on_lavapipe_with("REPOSE_STAGING=4099 ", dir);
  // A staging buffer of one byte has no halves to take turns: a piece waits for the one before.
  CHECK(state_after("drop_sphere.toml", "vulkan", 50, 0, dir, "REPOSE_STAGING=1 ") ==
        state_after("drop_sphere.toml", "cpu", 50, 0, dir));
  for (const char* bad : {"0", "4k", "67108865"}) check_refused("REPOSE_STAGING", bad, "vulkan");
}
