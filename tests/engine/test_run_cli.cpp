// `repose run` as a user runs it: a good case writes its results; a bad case names file, key
// and line, exits non-zero and writes nothing; the same case gives the same state bytes.
#include <catch2/catch.hpp>

#include "tests/cli_support.h"
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

repose::test::CliRun run_cli(const std::string& args) { return repose::test::run_repose(args); }

fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("repose_test_" + name);
  fs::remove_all(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

}  // namespace

TEST_CASE("repose run writes summary, frames and a state file that repeats byte for byte", "[engine][cli]") {
  fs::path out = fresh_dir("run_ok");
  fs::create_directories(out);
  std::string base = std::string("run ") + REPOSE_SOURCE_DIR + "/cases/settle_box.toml --backend cpu --steps 300 --quiet";
  auto a = run_cli(base + " --out " + (out / "a").string() + " --state-out " + (out / "a.state").string());
  REQUIRE(a.status == 0);
  CHECK(fs::exists(out / "a" / "summary.json"));
  CHECK(fs::exists(out / "a" / "frames"));
  auto b = run_cli(base + " --threads 1 --out " + (out / "b").string() + " --state-out " + (out / "b.state").string());
  REQUIRE(b.status == 0);
  auto c = run_cli(std::string("run ") + REPOSE_SOURCE_DIR + "/cases/settle_box.toml --backend vulkan --steps 300 --quiet --out " +
                   (out / "c").string() + " --state-out " + (out / "c.state").string());
  REQUIRE(c.status == 0);
  std::string sa = slurp(out / "a.state");
  CHECK(sa.size() > 100000);
  CHECK(sa == slurp(out / "b.state"));
  CHECK(sa == slurp(out / "c.state"));
  std::string summary = slurp(out / "a" / "summary.json");
  CHECK(summary.find("\"rayleigh_time\"") != std::string::npos);
  CHECK(summary.find("\"kinetic_energy\"") != std::string::npos);
  CHECK(summary.find("\"wall_forces\"") != std::string::npos);
}

TEST_CASE("bad case files: file, key and line named, non-zero exit, nothing written", "[engine][cli]") {
  struct Bad {
    const char* what;
    const char* toml;
    const char* key;
    int line;
  };
  const char* head =
      "[simulation]\nend_time = 0.1\nrayleigh_fraction = 0.2\n"               // lines 1-3
      "[[material]]\nname = \"g\"\ndensity = 1000\nshear_modulus = 1e6\npoisson = 0.3\n";  // 4-8
  const Bad cases[] = {
      {"unknown key", "[[interaction]]\nmaterials = [\"g\", \"g\"]\nrestitution = 0.5\nstatic_friction = 0.5\nrolling_friction = 0.0\nfriction_coef = 1\n"
                      "[[sphere]]\nmaterial = \"g\"\nradius = 0.01\nposition = [0, 0, 0]\n", "friction_coef", 14},
      {"negative radius", "[[interaction]]\nmaterials = [\"g\", \"g\"]\nrestitution = 0.5\nstatic_friction = 0.5\nrolling_friction = 0.0\n"
                          "[[sphere]]\nmaterial = \"g\"\nradius = -0.01\nposition = [0, 0, 0]\n", "radius", 16},
      {"restitution above 1", "[[interaction]]\nmaterials = [\"g\", \"g\"]\nrestitution = 1.5\nstatic_friction = 0.5\nrolling_friction = 0.0\n"
                              "[[sphere]]\nmaterial = \"g\"\nradius = 0.01\nposition = [0, 0, 0]\n", "restitution", 11},
      {"overlapping spheres", "[[interaction]]\nmaterials = [\"g\", \"g\"]\nrestitution = 0.5\nstatic_friction = 0.5\nrolling_friction = 0.0\n"
                              "[[sphere]]\nmaterial = \"g\"\nradius = 0.01\nposition = [0, 0, 0]\n"
                              "[[sphere]]\nmaterial = \"g\"\nradius = 0.01\nposition = [0.01, 0, 0]\n", "sphere", 18},
  };
  for (const Bad& bad : cases) {
    fs::path dir = fresh_dir("bad_case");
    fs::create_directories(dir);
    fs::path file = dir / "bad.toml";
    std::ofstream(file) << head << bad.toml;
    fs::path out = dir / "out";
    auto r = run_cli("run " + file.string() + " --backend cpu --out " + out.string() + " --state-out " +
                     (dir / "s.state").string());
    INFO(bad.what << ": exit " << r.status << ", message: " << r.output);
    CHECK(r.status != 0);
    CHECK(r.output.find("bad.toml") != std::string::npos);
    CHECK(r.output.find(bad.key) != std::string::npos);
    CHECK(r.output.find(":" + std::to_string(bad.line)) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(dir / "s.state"));
  }
}

TEST_CASE("a time step above the stable limit is refused", "[engine][cli]") {
  fs::path dir = fresh_dir("bad_dt");
  fs::create_directories(dir);
  fs::path file = dir / "dt.toml";
  std::ofstream(file) << "[simulation]\nend_time = 0.1\nrayleigh_fraction = 1.5\n"
                         "[[material]]\nname = \"g\"\ndensity = 1000\nshear_modulus = 1e6\npoisson = 0.3\n"
                         "[[interaction]]\nmaterials = [\"g\", \"g\"]\nrestitution = 0.5\nstatic_friction = 0.5\nrolling_friction = 0.0\n"
                         "[[sphere]]\nmaterial = \"g\"\nradius = 0.01\nposition = [0, 0, 0]\n";
  auto r = run_cli("run " + file.string() + " --backend cpu --out " + (dir / "out").string());
  INFO(r.output);
  CHECK(r.status != 0);
  CHECK(r.output.find("dt.toml:3") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out"));
}
