// Every kind of mistake in a case file gives a CaseError "FILE:LINE: KEY: what", with the line
// of the offending value (or of its table when the value is missing).
#include <catch2/catch.hpp>

#include <string>

#include "case/case_loader.h"

using namespace repose;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

// A small valid case; each test breaks one thing in it.
const std::string kValid = R"([simulation]
end_time = 0.1
rayleigh_fraction = 0.2

[[material]]
name = "grain"
density = 850
shear_modulus = 1.09e6
poisson = 0.32

[[material]]
name = "steel"
preset = "q235_steel"

[[interaction]]
materials = ["grain", "grain"]
restitution = 0.42
static_friction = 0.457
rolling_friction = 0.039

[[interaction]]
materials = ["grain", "steel"]
restitution = 0.43
static_friction = 0.67
rolling_friction = 0.0476

[[sphere]]
material = "grain"
radius = 0.005
position = [0, 0, 0.1]

[[wall]]
name = "floor"
type = "plane"
material = "steel"
point = [0, 0, 0]
normal = [0, 0, 1]
)";

// The text with `from` (which must occur exactly once) replaced by `to`.
std::string edited(const std::string& text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  REQUIRE(text.find(from, at + 1) == std::string::npos);
  return text.substr(0, at) + to + text.substr(at + from.size());
}

// 1-based line of the first occurrence of needle.
int line_of(const std::string& text, const std::string& needle) {
  size_t at = text.find(needle);
  REQUIRE(at != std::string::npos);
  return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
}

std::string error_of(const std::string& text, const std::vector<CaseOverride>& overrides = {}) {
  try {
    load_case_from_string(text, "cases/bad.toml", overrides);
  } catch (const CaseError& error) {
    return error.what();
  }
  FAIL("the case loaded without a CaseError");
  return "";
}

std::string at(int line, const std::string& key) {
  return "cases/bad.toml:" + std::to_string(line) + ": " + key + ": ";
}

}  // namespace

TEST_CASE("the valid base case loads") { CHECK_NOTHROW(load_case_from_string(kValid, "cases/bad.toml")); }

TEST_CASE("unknown keys are named with their line and the nearest allowed key") {
  std::string text = edited(kValid, "density = 850", "densty = 850");
  std::string message = error_of(text);
  CHECK_THAT(message, StartsWith(at(line_of(text, "densty"), "material[0].densty")));
  CHECK_THAT(message, Contains("did you mean 'density'?"));

  text = edited(kValid, "[simulation]", "[simulaton]");
  CHECK_THAT(error_of(text), StartsWith(at(1, "simulaton")) && Contains("did you mean 'simulation'?"));

  text = edited(kValid, "end_time = 0.1", "end_time = 0.1\nend_tme = 0.2");
  CHECK_THAT(error_of(text), StartsWith(at(3, "simulation.end_tme")) && Contains("'end_time'"));

  text = kValid + "\n[[fill]]\nmaterial = \"grain\"\ncount = 10\nradius = 0.005\nbox = { min = [0, 0, 0], mx = [1, 1, 1] }\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "mx ="), "fill[0].box.mx")) && Contains("'max'"));

  text = edited(kValid, "type = \"plane\"", "typ = \"plane\"");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "typ ="), "wall[0].typ")) && Contains("did you mean 'type'?"));

  // A key of another wall type is unknown for this one.
  text = edited(kValid, "normal = [0, 0, 1]", "normal = [0, 0, 1]\nradius = 0.1");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "radius = 0.1"), "wall[0].radius")) &&
                                 Contains("plane [[wall]]"));
}

TEST_CASE("missing required values point at their table") {
  std::string text = edited(kValid, "end_time = 0.1\n", "");
  CHECK_THAT(error_of(text), StartsWith(at(1, "simulation.end_time")) && Contains("missing"));

  text = edited(kValid, "density = 850\n", "");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "name = \"grain\"") - 1, "material[0].density")) &&
                                 Contains("missing"));

  text = edited(kValid, "rolling_friction = 0.039\n", "");
  CHECK_THAT(error_of(text), StartsWith(at(15, "interaction[0].rolling_friction")));

  text = edited(kValid, "rayleigh_fraction = 0.2\n", "");
  CHECK_THAT(error_of(text), StartsWith(at(1, "simulation.dt")) && Contains("rayleigh_fraction"));

  text = edited(kValid, "[simulation]\nend_time = 0.1\nrayleigh_fraction = 0.2\n", "");
  CHECK_THAT(error_of(text), StartsWith("cases/bad.toml: simulation: missing [simulation]"));
}

TEST_CASE("values of the wrong type are named") {
  std::string text = edited(kValid, "end_time = 0.1", "end_time = \"0.1\"");
  CHECK_THAT(error_of(text), StartsWith(at(2, "simulation.end_time")) &&
                                 Contains("expected a number, got a string"));

  text = edited(kValid, "position = [0, 0, 0.1]", "position = [0, 0.1]");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "position"), "sphere[0].position")) &&
                                 Contains("3 numbers"));

  text = kValid + "\n[[fill]]\nmaterial = \"grain\"\ncount = 2.5\nradius = 0.005\nbox = { min = [0, 0, 0], max = [1, 1, 1] }\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "count = 2.5"), "fill[0].count")) &&
                                 Contains("expected an integer, got a float"));

  text = edited(kValid, "[[sphere]]", "[sphere]");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "[sphere]"), "sphere")) && Contains("[[sphere]]"));
}

TEST_CASE("radius must be positive") {
  std::string text = edited(kValid, "radius = 0.005", "radius = -0.005");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "radius"), "sphere[0].radius")) &&
                                 Contains("greater than 0"));
  text = edited(kValid, "radius = 0.005", "radius = 0");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "radius"), "sphere[0].radius")));
}

TEST_CASE("restitution must lie in 0 < e <= 1") {
  for (const char* bad : {"0", "-0.1", "1.01"}) {
    std::string text = edited(kValid, "restitution = 0.43", std::string("restitution = ") + bad);
    CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "restitution = " + std::string(bad) + "\n"),
                                             "interaction[1].restitution")) &&
                                   Contains("outside (0, 1]"));
  }
  CHECK_NOTHROW(load_case_from_string(edited(kValid, "restitution = 0.43", "restitution = 1.0"), "ok.toml"));
}

TEST_CASE("friction must not be negative") {
  std::string text = edited(kValid, "static_friction = 0.67", "static_friction = -0.1");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "-0.1"), "interaction[1].static_friction")) &&
                                 Contains("negative"));
  text = edited(kValid, "rolling_friction = 0.039", "rolling_friction = -1e-3");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "-1e-3"), "interaction[0].rolling_friction")));
  CHECK_NOTHROW(load_case_from_string(edited(kValid, "static_friction = 0.67", "static_friction = 0"), "ok.toml"));
}

TEST_CASE("Poisson's ratio must lie between -1 and 0.5") {
  for (const char* bad : {"0.5", "-1", "0.7"}) {
    std::string text = edited(kValid, "poisson = 0.32", std::string("poisson = ") + bad);
    CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "poisson"), "material[0].poisson")) &&
                                   Contains("outside (-1, 0.5)"));
  }
  std::string text = edited(kValid, "preset = \"q235_steel\"", "preset = \"q235_steel\"\npoisson = 0.5");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "poisson = 0.5"), "material[1].poisson")));
}

TEST_CASE("unknown material names are named with a suggestion") {
  std::string text = edited(kValid, "material = \"grain\"\nradius", "material = \"grian\"\nradius");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "grian"), "sphere[0].material")) &&
                                 Contains("unknown material 'grian'") && Contains("did you mean 'grain'?"));
  text = edited(kValid, "materials = [\"grain\", \"steel\"]", "materials = [\"grain\", \"steal\"]");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "steal"), "interaction[1].materials")) &&
                                 Contains("did you mean 'steel'?"));
  text = edited(kValid, "preset = \"q235_steel\"", "preset = \"q235\"");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "q235\""), "material[1].preset")) &&
                                 Contains("'q235_steel'"));
}

TEST_CASE("a material pair that meets needs an interaction") {
  // Particles against the floor: reported at the wall, the later of the two, naming the sphere.
  std::string text = edited(kValid, "[[interaction]]\nmaterials = [\"grain\", \"steel\"]",
                            "[[interaction]]\nmaterials = [\"steel\", \"steel\"]");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "material = \"steel\""), "wall[0].material")) &&
                                 Contains("'grain' meets 'steel' (sphere[0].material, line " +
                                          std::to_string(line_of(text, "material = \"grain\"")) + ")"));
  // Particles against each other: needs two of them.
  text = edited(kValid, "materials = [\"grain\", \"grain\"]", "materials = [\"steel\", \"steel\"]");
  CHECK_NOTHROW(load_case_from_string(text, "ok.toml"));
  text += "\n[[sphere]]\nmaterial = \"grain\"\nradius = 0.005\nposition = [0, 0, 0.2]\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "material = \"grain\""), "sphere[0].material")) &&
                                 Contains("particles of 'grain' touch each other"));
}

TEST_CASE("a duplicate interaction is named with the first one's line") {
  std::string text = kValid + "\n[[interaction]]\nmaterials = [\"steel\", \"grain\"]\nrestitution = 0.5\n"
                              "static_friction = 0.5\nrolling_friction = 0.01\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "[\"steel\", \"grain\"]"), "interaction[2].materials")) &&
                                 Contains("duplicate") && Contains("line 21"));
}

TEST_CASE("a time step above the Rayleigh time is refused") {
  // Rayleigh time of the 5 mm grain sphere: 4.7228e-4 s.
  std::string text = edited(kValid, "rayleigh_fraction = 0.2", "dt = 5e-4");
  CHECK_THAT(error_of(text), StartsWith(at(3, "simulation.dt")) && Contains("Rayleigh time 0.000472278") &&
                                 Contains("sphere[0] (line 27"));
  CHECK_NOTHROW(load_case_from_string(edited(kValid, "rayleigh_fraction = 0.2", "dt = 4.7e-4"), "ok.toml"));

  text = edited(kValid, "rayleigh_fraction = 0.2", "rayleigh_fraction = 1.5");
  CHECK_THAT(error_of(text), StartsWith(at(3, "simulation.rayleigh_fraction")) && Contains("above 1"));
  CHECK_NOTHROW(load_case_from_string(edited(kValid, "rayleigh_fraction = 0.2", "rayleigh_fraction = 1"), "ok.toml"));

  text = edited(kValid, "rayleigh_fraction = 0.2", "rayleigh_fraction = 0.2\ndt = 1e-5");
  CHECK_THAT(error_of(text), StartsWith(at(4, "simulation.dt")) && Contains("not both"));
  text = edited(kValid, "rayleigh_fraction = 0.2", "dt = 0");
  CHECK_THAT(error_of(text), StartsWith(at(3, "simulation.dt")) && Contains("greater than 0"));
}

TEST_CASE("overlapping explicit spheres name both lines") {
  std::string text = kValid + "\n[[sphere]]\nmaterial = \"grain\"\nradius = 0.005\nposition = [0, 0.008, 0.1]\n";
  int second = line_of(text, "[[sphere]]\nmaterial = \"grain\"\nradius = 0.005\nposition = [0, 0.008");
  CHECK_THAT(error_of(text), StartsWith(at(second, "sphere[1]")) && Contains("overlaps sphere[0] (line 27)") &&
                                 Contains("0.008 m apart"));
  // Touching is not overlapping.
  CHECK_NOTHROW(load_case_from_string(
      kValid + "\n[[sphere]]\nmaterial = \"grain\"\nradius = 0.005\nposition = [0, 0.01, 0.1]\n", "ok.toml"));
}

TEST_CASE("a fill that cannot place its count says how many fit") {
  std::string text = kValid + "\n[[fill]]\nmaterial = \"grain\"\ncount = 1000\nradius = 0.005\n"
                              "box = { min = [0.2, 0.2, 0], max = [0.25, 0.25, 0.05] }\n";
  std::string message = error_of(text);
  CHECK_THAT(message, StartsWith(at(line_of(text, "[[fill]]"), "fill[0]")) && Contains("of the 1000 spheres"));
  // Random sequential addition jams near 38 % solid: a 4 cm cube of centres holds a few dozen.
  int fitted = std::stoi(message.substr(message.find("only ") + 5));
  CHECK(fitted > 10);
  CHECK(fitted < 120);
}

TEST_CASE("end time must be positive") {
  for (const char* bad : {"0", "-1"}) {
    std::string text = edited(kValid, "end_time = 0.1", std::string("end_time = ") + bad);
    CHECK_THAT(error_of(text), StartsWith(at(2, "simulation.end_time")) && Contains("greater than 0"));
  }
}

TEST_CASE("TOML syntax errors carry file, line and column") {
  std::string text = edited(kValid, "poisson = 0.32", "poisson = 0.32 0.1");
  CHECK_THAT(error_of(text), StartsWith("cases/bad.toml:" + std::to_string(line_of(text, "poisson")) + ":16: ") &&
                                 Contains("TOML syntax"));
  text = edited(kValid, "end_time = 0.1", "end_time = 0.1\nend_time = 0.2");
  CHECK_THAT(error_of(text), StartsWith("cases/bad.toml:3:"));
}

TEST_CASE("other checks: moduli, option words, lattices, wall geometry") {
  std::string text = edited(kValid, "shear_modulus = 1.09e6", "shear_modulus = 1.09e6\nyoungs_modulus = 2.9e6");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "youngs"), "material[0].youngs_modulus")) && Contains("not both"));

  text = kValid + "\n[contact]\ncoulomb_cap = \"sprng\"\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "sprng"), "contact.coulomb_cap")) &&
                                 Contains("did you mean 'spring'?"));

  // LIGGGHTS's relative rolling torque takes R*: EDEM's centre-of-mass lever does not go with it.
  text = kValid + "\n[contact]\nrolling_omega = \"relative\"\nrolling_lever = \"centre\"\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "rolling_lever"), "contact.rolling_lever")) &&
                                 Contains("R*"));

  text = kValid + "\n[[lattice]]\nmaterial = \"grain\"\ntype = \"sc\"\nmin = [0, 0, 0]\nmax = [0.1, 0.1, 0.1]\n"
                  "spacing = 0.009\nradius = 0.005\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "spacing = 0.009"), "lattice[0].spacing")));

  text = kValid + "\n[[lattice]]\nmaterial = \"grain\"\ntype = \"sc\"\nmin = [0, 0, 0]\nmax = [0.1, 0.1, 0.1]\n"
                  "spacing = 0.01\nradius = 0.005\ncount = 1001\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "[[lattice]]"), "lattice[0]")) &&
                                 Contains("only 1000 sites fit"));

  // A lattice site on top of an explicit sphere.
  text = kValid + "\n[[lattice]]\nmaterial = \"grain\"\ntype = \"sc\"\nmin = [-0.005, -0.005, 0.095]\n"
                  "max = [0.1, 0.1, 0.2]\nspacing = 0.01\nradius = 0.005\n";
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "[[lattice]]"), "lattice[0]")) &&
                                 Contains("overlaps sphere[0] (line 27)"));

  text = edited(kValid, "normal = [0, 0, 1]", "normal = [0, 0, 0]");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "normal"), "wall[0].normal")) && Contains("zero vector"));

  text = edited(kValid, "type = \"plane\"", "type = \"plain\"");
  CHECK_THAT(error_of(text), StartsWith(at(line_of(text, "plain"), "wall[0].type")) && Contains("'plane'"));

  text = edited(kValid, "name = \"grain\"", "name = \"gr.ain\"");
  CHECK_THAT(error_of(text), StartsWith(at(6, "material[0].name")) && Contains("not a usable name"));
}

TEST_CASE("a case without particles or materials is refused") {
  std::string text = edited(kValid, "[[sphere]]\nmaterial = \"grain\"\nradius = 0.005\nposition = [0, 0, 0.1]\n", "");
  CHECK_THAT(error_of(text), Contains("no particles"));
}

TEST_CASE("errors in values set by overrides name the key") {
  std::string message = error_of(kValid, {{"material.grain.poisson", "0.6"}});
  CHECK_THAT(message, StartsWith("cases/bad.toml: material[0].poisson: ") && Contains("outside (-1, 0.5)"));
  message = error_of(kValid, {{"material.5.density", "1"}});
  CHECK_THAT(message, StartsWith("cases/bad.toml: override material.5.density=1: ") && Contains("2 elements"));
  message = error_of(kValid, {{"material.grian.density", "1"}});
  CHECK_THAT(message, Contains("no material is named 'grian'") && Contains("did you mean 'grain'?"));
  message = error_of(kValid, {{"simulation.end_time.x", "1"}});
  CHECK_THAT(message, Contains("single value"));
  message = error_of(kValid, {{"simulaton.end_time", "1"}});
  CHECK_THAT(message, StartsWith("cases/bad.toml: simulaton: ") && Contains("did you mean 'simulation'?"));
}

TEST_CASE("a missing case file is a CaseError") {
  try {
    load_case("/nonexistent/case.toml");
    FAIL("loaded a missing file");
  } catch (const CaseError& error) {
    CHECK_THAT(std::string(error.what()), StartsWith("/nonexistent/case.toml: cannot read"));
  }
}
