// What a valid case turns into: defaults, presets, overrides, and the shipped example cases.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <string>

#include "case/case_loader.h"
#include "case/case_override.h"
#include "case/material_presets.h"
#include "case/particle_factory.h"
#include "case/time_step.h"

using namespace repose;
using Catch::Matchers::Contains;

namespace {

const std::string kCase = R"([simulation]
end_time = 0.25
dt = 1e-5

[[material]]
preset = "cabbage"

[[material]]
name = "steel"
preset = "q235_steel"
poisson = 0.3

[[material]]
name = "rubber"
density = 1100
youngs_modulus = 5e6
poisson = 0.45

[[interaction]]
materials = ["cabbage", "cabbage"]
preset = ["cabbage", "cabbage"]

[[interaction]]
materials = ["steel", "cabbage"]
preset = ["q235_steel", "cabbage"]
restitution = 0.5

[[sphere]]
material = "cabbage"
radius = 0.08
position = [0, 0, 0.3]
velocity = [1, 0, 0]
angular_velocity = [0, 2, 0]

[[wall]]
name = "floor"
type = "plane"
material = "steel"
point = [0, 0, 0]
normal = [0, 0, 2]
motion = { velocity = [0, 0, 0.1], start = 0.1, stop = 0.2 }

[[wall]]
type = "cylinder"
material = "steel"
base = [0, 0, 0]
radius = 0.5
height = 1
)";

}  // namespace

TEST_CASE("defaults are EDEM's and the name is the file's stem") {
  CaseSpec spec = load_case_from_string(kCase, "some/dir/my_case.toml");
  CHECK(spec.path == "some/dir/my_case.toml");
  CHECK(spec.name == "my_case");
  CHECK(spec.seed == 1);
  CHECK(spec.gravity == Vec3d{0, 0, -9.81});
  CHECK(spec.integrator == Integrator::VelocityVerlet);
  CHECK(spec.contact.coulomb_cap == CoulombCap::SpringAndDamper);
  CHECK(spec.contact.normal_attraction == NormalAttraction::Allow);
  CHECK(spec.contact.rolling == RollingModel::ConstantTorque);
  CHECK(spec.contact.rolling_omega == RollingOmega::Own);
  CHECK(spec.contact.rolling_lever == RollingLever::Centre);
  CHECK(spec.neighbour.skin < 0);
  CHECK(spec.neighbour.rebuild_interval == 0);
  CHECK(spec.output.interval == 0);
  CHECK(spec.output.vtk);
  CHECK(spec.time.dt == 1e-5);
  CHECK(!spec.time.rayleigh_fraction);
  CHECK(spec.time.end_time == 0.25);
  CHECK(spec.time.where.key == "simulation.dt");
  CHECK(spec.time.where.line == 3);
}

TEST_CASE("every option word is read") {
  std::string text = kCase + R"(
[contact]
coulomb_cap = "spring"
normal_attraction = "clip"
rolling = "none"
rolling_omega = "relative"
rolling_lever = "sphere"

[neighbour]
skin = 0.002
rebuild_interval = 10

[output]
interval = 0.01
vtk = false
)";
  text.replace(text.find("dt = 1e-5"), 9, "rayleigh_fraction = 0.3\nseed = 99\nname = \"x\"\ngravity = [0, -9.8, 0]\n"
                                          "integrator = \"symplectic_euler\"");
  CaseSpec spec = load_case_from_string(text, "c.toml");
  CHECK(spec.name == "x");
  CHECK(spec.seed == 99);
  CHECK(spec.gravity == Vec3d{0, -9.8, 0});
  CHECK(spec.integrator == Integrator::SymplecticEuler);
  CHECK(spec.time.rayleigh_fraction == 0.3);
  CHECK(spec.contact.coulomb_cap == CoulombCap::SpringOnly);
  CHECK(spec.contact.normal_attraction == NormalAttraction::Clip);
  CHECK(spec.contact.rolling == RollingModel::None);
  CHECK(spec.contact.rolling_omega == RollingOmega::Relative);
  CHECK(spec.contact.rolling_lever == RollingLever::Sphere);  // LIGGGHTS's, with the relative torque
  CHECK(spec.neighbour.skin == 0.002);
  CHECK(spec.neighbour.rebuild_interval == 10);
  CHECK(spec.output.interval == 0.01);
  CHECK(!spec.output.vtk);
}

TEST_CASE("presets load and can be overridden key by key") {
  CaseSpec spec = load_case_from_string(kCase, "c.toml");
  REQUIRE(spec.materials.size() == 3);
  const Material& cabbage = spec.materials[0];
  CHECK(cabbage.name == "cabbage");
  CHECK(cabbage.density == 850);
  CHECK(cabbage.shear_modulus == 1.09e6);
  CHECK(cabbage.poisson == 0.32);
  CHECK(cabbage.youngs_modulus == Approx(2.8776e6).epsilon(1e-12));
  CHECK(cabbage.where.key == "material[0]");
  CHECK(cabbage.where.line == 5);

  const Material& steel = spec.materials[1];
  CHECK(steel.density == 7850);
  CHECK(steel.shear_modulus == 8.2e10);
  CHECK(steel.poisson == 0.3);  // the override

  const Material& rubber = spec.materials[2];
  CHECK(rubber.youngs_modulus == 5e6);
  CHECK(rubber.shear_modulus == Approx(5e6 / 2.9).epsilon(1e-12));

  REQUIRE(spec.interactions.size() == 2);
  CHECK(spec.interactions[0].restitution == 0.42);
  CHECK(spec.interactions[0].static_friction == 0.457);
  CHECK(spec.interactions[0].rolling_friction == 0.039);
  CHECK(spec.interactions[1].material_a == 1);
  CHECK(spec.interactions[1].material_b == 0);
  CHECK(spec.interactions[1].restitution == 0.5);
  CHECK(spec.interactions[1].static_friction == 0.67);
  CHECK(spec.interactions[1].rolling_friction == 0.0476);

  // Every preset is a usable material and every interaction preset names two presets.
  for (const auto& preset : material_presets()) {
    CHECK(preset.density > 0);
    CHECK(preset.shear_modulus > 0);
    CHECK(preset.poisson > -1);
    CHECK(preset.poisson < 0.5);
  }
  for (const auto& preset : interaction_presets()) {
    CHECK(find_material_preset(preset.material_a));
    CHECK(find_material_preset(preset.material_b));
  }
}

TEST_CASE("spheres and walls carry their values and lines") {
  CaseSpec spec = load_case_from_string(kCase, "c.toml");
  REQUIRE(spec.spheres.size() == 1);
  const SphereSpec& sphere = spec.spheres[0];
  CHECK(sphere.radius == 0.08);
  CHECK(sphere.position == Vec3d{0, 0, 0.3});
  CHECK(sphere.velocity == Vec3d{1, 0, 0});
  CHECK(sphere.angular_velocity == Vec3d{0, 2, 0});
  CHECK(sphere.where.key == "sphere[0]");
  CHECK(sphere.where.line == 28);

  REQUIRE(spec.walls.size() == 2);
  CHECK(spec.walls[0].name == "floor");
  CHECK(spec.walls[0].normal == Vec3d{0, 0, 1});  // normalised
  CHECK(spec.walls[0].motion.velocity == Vec3d{0, 0, 0.1});
  CHECK(spec.walls[0].motion.start_time == 0.1);
  CHECK(spec.walls[0].motion.stop_time == 0.2);
  CHECK(spec.walls[1].name == "wall[1]");
  CHECK(spec.walls[1].type == WallSpec::Type::Cylinder);
  CHECK(spec.walls[1].axis == Vec3d{0, 0, 1});
  CHECK(spec.walls[1].radius == 0.5);
  CHECK(spec.walls[1].material == 1);
}

TEST_CASE("overrides set values by index, by name and by material pair") {
  std::vector<CaseOverride> overrides = {
      {"simulation.end_time", "0.5"},
      {"simulation.gravity", "[0, 0, -9.81]"},  // the file has no gravity: set the array ...
      {"simulation.gravity.2", "-9.8"},          // ... then one element of it
      {"material.cabbage.density", "900"},
      {"material.1.poisson", "0.25"},
      {"interaction.cabbage/steel.restitution", "0.6"},
      {"interaction.0.static_friction", "0.3"},
      {"wall.floor.point", "[0, 0, -0.1]"},
      {"sphere.0.radius", "0.07"},
      {"neighbour.skin", "0.001"},           // a table the file does not have
      {"contact.normal_attraction", "clip"},  // a bare word is a string
      {"contact.rolling", "\"none\""},
  };
  CaseSpec spec = load_case_from_string(kCase, "c.toml", overrides);
  CHECK(spec.time.end_time == 0.5);
  CHECK(spec.gravity[2] == -9.8);
  CHECK(spec.materials[0].density == 900);
  CHECK(spec.materials[1].poisson == 0.25);
  CHECK(spec.interactions[1].restitution == 0.6);
  CHECK(spec.interactions[0].static_friction == 0.3);
  CHECK(spec.walls[0].point == Vec3d{0, 0, -0.1});
  CHECK(spec.spheres[0].radius == 0.07);
  CHECK(spec.neighbour.skin == 0.001);
  CHECK(spec.contact.normal_attraction == NormalAttraction::Clip);
  CHECK(spec.contact.rolling == RollingModel::None);

  // Later overrides win, and "KEY=VALUE" text splits at the first '='.
  CaseOverride parsed = parse_override("simulation.end_time=0.75");
  CHECK(parsed.key == "simulation.end_time");
  CHECK(parsed.value == "0.75");
  spec = load_case_from_string(kCase, "c.toml", {{"simulation.end_time", "0.5"}, parsed});
  CHECK(spec.time.end_time == 0.75);
  CHECK_THROWS_AS(parse_override("no equals sign"), CaseError);

  // Switching dt for rayleigh_fraction needs the old key removed (an empty value): both is an error.
  CHECK_THROWS_WITH(load_case_from_string(kCase, "c.toml", {{"simulation.rayleigh_fraction", "0.2"}}),
                    Contains("not both"));
  spec = load_case_from_string(kCase, "c.toml", {{"simulation.dt", ""}, {"simulation.rayleigh_fraction", "0.2"}});
  CHECK(!spec.time.dt);
  CHECK(spec.time.rayleigh_fraction == 0.2);
  // An empty value on an array element drops it.
  spec = load_case_from_string(kCase, "c.toml", {{"wall.floor", ""}});
  REQUIRE(spec.walls.size() == 1);
  CHECK(spec.walls[0].type == WallSpec::Type::Cylinder);
  CHECK_THROWS_WITH(load_case_from_string(kCase, "c.toml", {{"output.interval", ""}}),
                    Contains("there is no output.interval to remove"));
}

TEST_CASE("apply_override works on a parsed TOML table") {
  toml::table root = toml::parse("[a]\nb = [1, 2]\n[[m]]\nname = \"x\"\nv = 1\n");
  apply_override(root, "a.b.1", "5");
  apply_override(root, "m.x.v", "{ q = 1 }");
  apply_override(root, "c.d", "true");
  CHECK(root["a"]["b"][1].value<int64_t>() == 5);
  CHECK(root["m"][0]["v"]["q"].value<int64_t>() == 1);
  CHECK(root["c"]["d"].value<bool>() == true);
  CHECK_THROWS_AS(apply_override(root, "a..b", "1"), CaseError);
  CHECK_THROWS_WITH(apply_override(root, "a.b.7", "1", "f.toml"), Contains("there is no a.b[7]"));
}

TEST_CASE("every shipped case loads") {
  std::filesystem::path dir = std::filesystem::path(REPOSE_SOURCE_DIR) / "cases";
  std::set<std::string> loaded;
  // Every case under cases/ (campaign plans in cases/calibrate/ are not cases).
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    if (entry.path().parent_path().filename() == "calibrate") continue;
    INFO(entry.path().string());
    CaseSpec spec;
    REQUIRE_NOTHROW(spec = load_case(entry.path().string()));
    CHECK((!spec.spheres.empty() || !spec.bodies.empty()));
    CHECK(resolve_dt(spec) <= rayleigh_time(spec));
    loaded.insert(entry.path().filename().string());
  }
  for (const char* name : {"settle_box.toml", "drop_sphere.toml", "bench_bed.toml", "bench_liggghts_bed.toml", "cylinder_settle.toml"})
    CHECK(loaded.count(name) == 1);
}

TEST_CASE("the shipped cases say what the issue asks for") {
  std::string dir = std::string(REPOSE_SOURCE_DIR) + "/cases/";
  CaseSpec settle = load_case(dir + "settle_box.toml");
  CHECK(settle.spheres.size() == 2400);
  CHECK(settle.spheres[0].radius == 0.005);
  CHECK(settle.time.rayleigh_fraction == 0.2);
  CHECK(settle.time.end_time == 0.5);
  CHECK(settle.output.interval == 0.05);
  CHECK(settle.walls.size() == 1);
  CHECK(settle.walls[0].type == WallSpec::Type::Box);

  CaseSpec drop = load_case(dir + "drop_sphere.toml");
  REQUIRE(drop.spheres.size() == 1);
  CHECK(drop.spheres[0].radius == 0.08);
  CHECK(drop.spheres[0].position[2] - drop.spheres[0].radius == Approx(0.5));
  CHECK(drop.materials[1].shear_modulus == 8.2e10);
  CHECK(drop.materials[1].poisson == 0.28);
  CHECK(drop.interactions[0].restitution == 0.43);
  CHECK(drop.interactions[0].static_friction == 0);

  CaseSpec bench = load_case(dir + "bench_bed.toml");
  CHECK(bench.spheres.size() == 50000);
  CHECK(bench.spheres[0].radius == 0.005);
  CHECK(bench.time.rayleigh_fraction == 0.2);

  // The LIGGGHTS benchmark bed: what the side-by-side comparison asks to be the same on both sides.
  CaseSpec peer = load_case(dir + "bench_liggghts_bed.toml");
  CHECK(peer.spheres.size() == 50000);
  CHECK(peer.neighbour.skin == 0.001);
  CHECK(peer.contact.coulomb_cap == CoulombCap::SpringOnly);
  CHECK(peer.contact.rolling_omega == RollingOmega::Relative);
  CHECK(peer.materials.size() == 1);
  CHECK(peer.walls[0].box_max[0] == 0.4472);
  CHECK(peer.time.rayleigh_fraction == 0.2);

  CaseSpec cylinder = load_case(dir + "cylinder_settle.toml");
  CHECK(cylinder.walls.size() == 2);
  CHECK(cylinder.walls[0].type == WallSpec::Type::Cylinder);
  CHECK(cylinder.walls[1].type == WallSpec::Type::Plane);
}

TEST_CASE("the complete example in docs/case-format.md loads") {
  std::ifstream in(std::string(REPOSE_SOURCE_DIR) + "/docs/case-format.md");
  std::stringstream doc;
  doc << in.rdbuf();
  std::string text = doc.str();
  size_t start = text.find("```toml\n");
  REQUIRE(start != std::string::npos);
  start += 8;
  std::string example = text.substr(start, text.find("```", start) - start);
  CaseSpec spec = load_case_from_string(example, "docs/case-format.md");
  CHECK(spec.spheres.size() > 2001);
  CHECK(spec.walls.size() == 3);
  CHECK(spec.contact.coulomb_cap == CoulombCap::SpringAndDamper);
}
