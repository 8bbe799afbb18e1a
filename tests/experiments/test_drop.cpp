// `repose experiment drop`: the seeds' free-fall test, measured by a simulated camera.
#include <catch2/catch.hpp>

#include "case/case_error.h"
#include "case/case_loader.h"
#include "experiments/drop.h"

using namespace repose;

TEST_CASE("drop experiment reproduces the LIGGGHTS rebound series (0.002)", "[experiments][drop]") {
  const std::string path = std::string(REPOSE_SOURCE_DIR) + "/cases/drop_sphere.toml";
  // LIGGGHTS 3.8 on these machines: sqrt(h/H) of the lowest point, e = 0.43 (docs/engineering.md).
  const std::pair<double, double> series[] = {{0.30, 0.4145}, {0.40, 0.4170}, {0.50, 0.4186}};
  for (auto [H, liggghts] : series) {
    CaseSpec spec = load_case(path, {{"experiment.drop_height", std::to_string(H)}});
    DropResult r = run_drop(spec);
    INFO("H = " << H << ": camera e = " << r.restitution << ", exact apex e = "
                << std::sqrt(r.rebound_height_exact / H) << ", LIGGGHTS " << liggghts);
    CHECK(std::abs(r.restitution - liggghts) < 0.002);
    // The camera (1000 fps, parabola through the top frames) agrees with the exact apex to 0.1 mm.
    CHECK(std::abs(r.rebound_height - r.rebound_height_exact) < 1e-4);
    CHECK(r.contact_time == Approx(0.014).margin(0.0015));  // docs/engineering.md: ~14 ms
    CHECK(r.trajectory.front().second == Approx(H).margin(1e-6));
  }
}

TEST_CASE("an unknown experiment type is a case error naming file, key and line", "[experiments][drop]") {
  std::string text =
      "[simulation]\nend_time = 1\ndt = 1e-5\n[experiment]\ntype = \"bounce\"\n"
      "[[material]]\nname = \"g\"\ndensity = 850\nshear_modulus = 1e6\npoisson = 0.3\n"
      "[[sphere]]\nmaterial = \"g\"\nradius = 0.05\nposition = [0, 0, 1]\n";
  try {
    load_case_from_string(text, "bad_drop.toml");
    FAIL("no error");
  } catch (const CaseError& e) {
    std::string m = e.what();
    INFO(m);
    CHECK(m.find("bad_drop.toml:5") != std::string::npos);
    CHECK(m.find("type") != std::string::npos);
  }
}
