// Multi-sphere clumps in the engine: free rigid-body motion, contact through one sub-sphere,
// no contacts inside a clump, the large-particle bucket, and bit-exact backends.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "engine/cpu_backend.h"
#include "engine/step_program.h"
#include "engine_test_support.h"
#include "io/state_validation.h"
#include "twin_kernels.h"

using namespace repose;
using namespace repose::test;

namespace {

double dot3d(const gpu::vec4& a, const gpu::vec4& b) {
  return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
}

std::unique_ptr<Simulation> broad_phase_run(const Model& m, const char* backend) {
  return std::make_unique<Simulation>(m, make_backend(backend, -1, 2, 64), KernelVariant{}, 25);
}

// Sub-spheres whose part meets no other body's (neighbour.h sub_may_pair) in the list just built.
size_t culled_subs(Simulation& sim) {
  gpu::Kernels k(dynamic_cast<CpuBackend&>(sim.backend()).buffers());
  k.PC = base_push(sim.model(), sim.layout(), sim.variant());
  size_t culled = 0;
  for (uint32_t i = 0; i < sim.model().n_particles; ++i) culled += k.sub_may_pair(i) ? 0 : 1;
  return culled;
}

// Parts whose sphere, at the rebuild just made, may meet fewer than all of the walls (part_near).
size_t parts_missing_walls(Simulation& sim) {
  const gpu::Buffers& buf = dynamic_cast<CpuBackend&>(sim.backend()).buffers();
  const uint32_t all = (1u << sim.model().walls.size()) - 1u;
  size_t parts = 0;
  for (uint32_t p = 0; p < sim.model().parts.size(); ++p) parts += (buf.parts[p].info.w & all) != all;
  return parts;
}

}  // namespace

TEST_CASE("a free clump keeps its angular momentum, energy and momentum") {
  CaseBuilder b;
  int grain = b.material(1000, 5e6, 0.3);
  b.interaction(grain, grain, 0.5, 0.4, 0.0);
  int t = b.clump_template("lumpy", lumpy_clump());
  b.clump(t, {0, 0, 0}, grain, {0.9, 0.1, -0.3, 0.2}, {0.1, -0.2, 0.05}, {30, -12, 21});
  b.spec.time.dt = 1e-5;
  auto sim = simulate(b.spec);
  const gpu::Body start = sim->state().bodies.at(0);
  double e0 = sim->kinetic_energy().rotational;
  sim->advance(20000);  // 0.2 s: ~1 revolution per 0.2 s at |w| ~ 39 rad/s... several tumbles
  const gpu::Body end = sim->state().bodies.at(0);
  // Torque-free: L is carried, not recomputed, so it is kept to the bit.
  CHECK(end.ang_mom.x == start.ang_mom.x);
  CHECK(end.ang_mom.y == start.ang_mom.y);
  CHECK(end.ang_mom.z == start.ang_mom.z);
  CHECK(end.vel.x == start.vel.x);
  // Energy 1/2 w.L changes only through the orientation. The scheme itself keeps it to 3e-9
  // here (checked in double); in float each step's rotation (|w| dt = 4e-4 rad) is rounded at
  // 6e-8, so the orientation can drift by up to 20,000 x 6e-8 = 1.2e-3 rad: bound 1e-3.
  double e1 = sim->kinetic_energy().rotational;
  CHECK(std::abs(e1 - e0) / e0 < 1e-3);
  // The orientation really changed (the body tumbles), and stays a unit quaternion.
  CHECK(std::abs(end.quat.w - start.quat.w) > 1e-3);
  CHECK(std::abs(dot3d(end.quat, end.quat) + double(end.quat.w) * end.quat.w - 1.0) < 1e-6);
  // The centre of mass moved ballistically (float positions: half an ulp of 0.02 m per step).
  CHECK(double(end.pos.x) == Approx(double(start.pos.x) + 0.1 * 0.2).margin(2e-5));
  // Sub-spheres stay rigidly attached: distances between them are unchanged.
  const auto& p = sim->state().pos;
  auto gap = [&](int i, int j) {
    double dx = p[i].x - p[j].x, dy = p[i].y - p[j].y, dz = p[i].z - p[j].z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  auto s = lumpy_clump();
  CHECK(gap(0, 1) == Approx(glm::length(s[0].centre - s[1].centre)).epsilon(1e-5));
  CHECK(gap(1, 2) == Approx(glm::length(s[1].centre - s[2].centre)).epsilon(1e-5));
}

TEST_CASE("sub-spheres of one clump exert no force on each other") {
  CaseBuilder b;
  int grain = b.material(1000, 5e6, 0.3);
  b.interaction(grain, grain, 0.5, 0.4, 0.0);
  int t = b.clump_template("lumpy", lumpy_clump());
  b.clump(t, {0, 0, 0}, grain);
  b.spec.time.dt = 1e-5;
  auto sim = simulate(b.spec);
  sim->advance(100);
  CHECK(sim->contacts() == 0);
  const gpu::Body& body = sim->state().bodies.at(0);
  CHECK(body.vel.x == 0.0f);
  CHECK(body.vel.z == 0.0f);
  CHECK(body.ang_mom.x == 0.0f);
}

// A vertical dumbbell falls on its lower sphere: the contact passes through the centre of mass,
// the body does not turn, and the rebound speed ratio is the pair's restitution as for one sphere
// (EDEM's damping makes e independent of the mass).
TEST_CASE("a clump dropped on one sub-sphere returns the sphere's restitution") {
  auto rebound = [](bool dumbbell, double e) {
    CaseBuilder b;
    int grain = b.material(1000, 5e6, 0.3);
    int steel = b.material(7800, 8e10, 0.3);
    b.interaction(grain, grain, e, 0.4, 0.0);
    b.interaction(grain, steel, e, 0.4, 0.0);
    const double r = 0.01, v0 = 1.0;
    if (dumbbell) {
      int t = b.clump_template("dumbbell", {{{0, 0, -0.8 * r}, r}, {{0, 0, 0.8 * r}, r}});
      b.clump(t, {0, 0, 1.8 * r + 1e-4}, grain, {1, 0, 0, 0}, {0, 0, -v0});
    } else {
      b.sphere({0, 0, r + 1e-4}, r, grain, {0, 0, -v0});
    }
    b.plane({0, 0, 0}, {0, 0, 1}, steel);
    b.spec.time.rayleigh_fraction = 0.01;
    auto sim = simulate(b.spec);
    double vz = 0;
    for (int k = 0; k < 400 && vz <= 0; ++k) {
      sim->advance(200);
      vz = dumbbell ? sim->state().bodies[0].vel.z : sim->state().vel[0].z;
      if (sim->contacts() > 0 && vz > 0) vz = 0;  // still in contact
    }
    if (dumbbell) CHECK(std::abs(sim->state().bodies[0].omega.x) < 1e-6);
    return vz / v0;
  };
  for (double e : {0.3, 0.7}) {
    double sphere = rebound(false, e), clump = rebound(true, e);
    INFO("e = " << e << ": sphere " << sphere << ", dumbbell " << clump);
    CHECK(sphere == Approx(e).epsilon(0.01));  // 1 %: the sphere check of test_contact_theory
    CHECK(clump == Approx(sphere).epsilon(0.005));
  }
}

// A dumbbell (two touching spheres of radius R, centres at y = +-R) rolls along x about its long
// axis on a plate, without slip. EDEM's rolling torque on each sphere is mu_r |Fn| L with L the
// distance from the contact point to the body's centre of mass, sqrt(R^2 + R^2); LIGGGHTS's
// multisphere takes the sphere's radius, L = R. Rigid-body theory: the torque mu_r M g L against
// rolling (I = 2/5 M R^2 about the long axis) decelerates it at 5 mu_r g L / (7 R), so it stops
// after s = 7 v0^2 R / (10 mu_r g L): 1/sqrt(2) of a lone sphere's distance with the centre lever.
TEST_CASE("a rolling dumbbell feels mu_r |Fn| |contact - centre|: stop distance 7 v0^2 R / (10 mu_r g L) (2 %)",
          "[engine][theory]") {
  const double R = 0.01, v0 = 0.5, mu_r = 0.05, g = 9.81;
  auto stop_distance = [&](RollingLever lever) {
    CaseBuilder b;
    int grain = b.material(1000, 1e7, 0.3);
    int floor = b.material(7800, 8e10, 0.3);
    b.interaction(grain, grain, 0.5, 0.8, mu_r);
    b.interaction(grain, floor, 0.5, 0.8, mu_r);
    b.spec.gravity = {0, 0, -g};
    b.spec.time.rayleigh_fraction = 0.2;
    b.spec.contact.rolling_lever = lever;
    // Start at each sphere's static overlap (it carries its own weight), rolling without slip.
    double m = 1000 * 4.0 / 3.0 * kPi * R * R * R;
    double E = 2e7 * 1.3, E_star = 1 / ((1 - 0.09) / E + (1 - 0.09) / (2 * 8e10 * 1.3));
    double d = std::pow(m * g / (4.0 / 3.0 * E_star * std::sqrt(R)), 2.0 / 3.0);
    int t = b.clump_template("dumbbell", {{{0, -R, 0}, R}, {{0, R, 0}, R}});
    b.clump(t, {0, 0, R - d}, grain, {1, 0, 0, 0}, {v0, 0, 0}, {0, v0 / (R - d), 0});
    b.plane({0, 0, 0}, {0, 0, 1}, floor);
    auto sim = simulate(b.spec, "cpu", 1, {}, 20);
    double x0 = sim->state().bodies[0].pos.x;
    while (sim->time() < 3.0) {
      sim->advance(20);
      if (sim->state().bodies[0].vel.x <= 0.001 * v0) return double(sim->state().bodies[0].pos.x) - x0;
    }
    return -1.0;
  };
  double sphere_lever = 7 * v0 * v0 / (10 * mu_r * g);
  double centre = stop_distance(RollingLever::Centre), sphere = stop_distance(RollingLever::Sphere);
  INFO("centre lever: stopped after " << centre << " m, theory " << sphere_lever / std::sqrt(2.0)
                                       << "; sphere lever: " << sphere << " m, theory " << sphere_lever);
  CHECK(centre == Approx(sphere_lever / std::sqrt(2.0)).epsilon(0.02));  // the sphere test's 2 %
  CHECK(sphere == Approx(sphere_lever).epsilon(0.02));
}

// Spheres spanning 10:1 in size: the big ones skip the grid (the large bucket), and the list
// must still hold every touching pair exactly once.
TEST_CASE("the contact list finds every touching pair when sizes span 10:1") {
  CaseBuilder b;
  int grain = b.material(1000, 5e6, 0.3);
  b.interaction(grain, grain, 0.5, 0.4, 0.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 6; ++k) b.sphere({0.1 * k, 0.05 * (k % 2), 0}, 0.05, grain);
  for (int k = 0; k < 1500; ++k)
    b.sphere({-0.06 + 0.62 * u(rng), -0.06 + 0.17 * u(rng), -0.06 + 0.12 * u(rng)},
             0.004 + 0.002 * u(rng), grain);
  b.spec.time.dt = 1e-6;
  Model model = build_model(b.spec);
  REQUIRE(model.large_radius < 0.05);  // the split applies
  Simulation sim(model, make_backend("cpu", -1, 2, 64));
  sim.advance(1);
  std::set<std::pair<uint32_t, uint32_t>> listed;
  const auto& s = sim.state();
  for (uint32_t c = 0; c < s.partner.size(); ++c) {
    auto pair = std::minmax(s.owner[c], s.partner[c]);
    CHECK(listed.insert(pair).second);  // no pair twice
  }
  size_t touching = 0;
  for (uint32_t i = 0; i < s.pos.size(); ++i)
    for (uint32_t j = i + 1; j < s.pos.size(); ++j) {
      double dx = s.pos[i].x - s.pos[j].x, dy = s.pos[i].y - s.pos[j].y, dz = s.pos[i].z - s.pos[j].z;
      if (std::sqrt(dx * dx + dy * dy + dz * dz) < double(s.pos[i].w) + s.pos[j].w) {
        ++touching;
        CHECK(listed.count({i, j}) == 1);
      }
    }
  CHECK(touching > 100);
  // Pairs of a large sphere (ids 0-5) and a small one sit in the small one's row, after the lower
  // id: a state file of this list is valid and reads back.
  CHECK(state_problem(s, sim.step(), sim.time()) == "");
}

// Clumps and lone spheres settling with walls: every byte equal on lavapipe and the CPU twin
// (1 and 2 threads) and for each kernel variant.
TEST_CASE("clumps are bit-exact between lavapipe and the CPU twin") {
  CaseBuilder b;
  b.spec = clump_pile();
  auto reference = simulate(b.spec, "cpu", 1);
  reference->advance(1500);
  REQUIRE(reference->contacts() > 50);
  std::string which;
  SECTION("cpu, 2 threads") {
    auto other = simulate(b.spec, "cpu", 2);
    other->advance(1500);
    CHECK(same_state(reference->state(), other->state(), &which));
  }
  SECTION("lavapipe, lean and full, contact and rows") {
    for (const char* v : {"contact,lean", "rows,full"}) {
      auto other = simulate(b.spec, "vulkan", 1, KernelVariant::parse(v));
      other->advance(1500);
      INFO(v << ": first difference in " << which);
      CHECK(same_state(reference->state(), other->state(), &which));
    }
  }
}

TEST_CASE("clumps with air drag and EPSD rolling springs: lavapipe equals the CPU twin") {
  CaseSpec spec = clump_pile();
  spec.air_drag.drag_coefficient = 1.0;
  spec.contact.rolling = RollingModel::ElasticPlastic;
  auto reference = simulate(spec, "cpu", 1);
  reference->advance(1500);
  REQUIRE(reference->contacts() > 50);
  auto other = simulate(spec, "vulkan", 1, KernelVariant::parse("rows,full"));
  other->advance(1500);
  std::string which;
  bool same = same_state(reference->state(), other->state(), &which);
  INFO("first difference in " << which);
  CHECK(same);
}

// As for spheres (test_bit_exact.cpp): clumps with rolling springs (state carried per contact)
// give the same bodies to the byte whatever the skin or rebuild interval.
TEST_CASE("clumps: the neighbour skin and the rebuild interval leave the bodies unchanged") {
  CaseSpec spec = clump_pile();
  spec.contact.rolling = RollingModel::ElasticPlastic;
  double skin = build_model(spec).skin;
  auto run = [&](double s, int interval) { return simulate_with_list(spec, s, interval, 1000); };
  auto reference = run(skin, 0);
  REQUIRE(reference->contacts() > 50);
  for (auto [s, interval] : {std::pair{0.2 * skin, 0}, std::pair{4.0 * skin, 0}, std::pair{skin, 1}}) {
    auto other = run(s, interval);
    INFO("skin " << s << " m, rebuild interval " << interval);
    CHECK(other->rebuilds() != reference->rebuilds());
    CHECK(same_bytes(reference->state().bodies, other->state().bodies));
    CHECK(same_bytes(reference->state().pos, other->state().pos));
  }
}

// The body-level broad phase (neighbour.h part_near) only skips pairs the grid walk would reject:
// the whole state, contact list included, is the same with it on and off, on both backends.
static void check_broad_phase_keeps_bytes(CaseSpec spec, uint64_t steps, size_t least_contacts) {
  spec.neighbour.body_broad_phase = true;
  Model on = build_model(spec);
  spec.neighbour.body_broad_phase = false;
  Model off = build_model(spec);
  REQUIRE((on.flags & gpu::kFlagBodyBroadPhase) != 0);
  REQUIRE((off.flags & gpu::kFlagBodyBroadPhase) == 0);
  for (const char* backend : {"cpu", "vulkan"}) {
    auto a = broad_phase_run(on, backend);
    auto b = broad_phase_run(off, backend);
    a->advance(steps);
    b->advance(steps);
    REQUIRE(a->contacts() > least_contacts);
    std::string which;
    bool same = same_state(a->state(), b->state(), &which);
    INFO(backend << ": first difference in " << which);
    CHECK(same);
  }
}

TEST_CASE("clumps: the body-level broad phase changes no byte, and culls bodies apart from the rest") {
  CaseSpec pile = clump_pile();
  pile.neighbour.body_broad_phase = true;
  // At the start the clumps fall 4 cm apart: some sub-spheres meet no other body, and skip the walk.
  auto first = broad_phase_run(build_model(pile), "cpu");
  size_t culled = culled_subs(*first);
  CHECK(culled > 0);
  CHECK(culled < first->model().n_particles);
  check_broad_phase_keeps_bytes(pile, 1500, 50);
}

// The pile poured into a cylinder onto a floor of two triangles, over a tilted rectangle: a
// part tests only the walls its sphere may meet (part_may_meet_wall), and the list is the same.
TEST_CASE("clumps: each part tests only the walls within its reach, and the list is the same") {
  CaseSpec pile = clump_pile();
  pile.walls.clear();
  WallSpec cylinder;
  cylinder.type = WallSpec::Type::Cylinder;
  cylinder.name = "cylinder";
  cylinder.base = {0.06, 0.06, -0.02};
  cylinder.radius = 0.1;
  cylinder.height = 0.4;
  cylinder.material = 1;
  WallSpec ramp;
  ramp.type = WallSpec::Type::Rectangle;
  ramp.name = "ramp";
  ramp.point = {0.1, 0.06, 0.02};
  ramp.normal = {-0.3, 0, 0.954};
  ramp.edge_axis = {0.954, 0, 0.3};
  ramp.size = {0.08, 0.1};
  ramp.material = 1;
  WallSpec floor;
  floor.type = WallSpec::Type::Mesh;
  floor.name = "floor";
  auto mesh = std::make_shared<WallMesh>();
  mesh->vertices = {{-0.1, -0.1, -0.012}, {0.3, -0.1, -0.012}, {0.3, 0.3, -0.012}, {-0.1, 0.3, -0.012}};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  floor.mesh = mesh;
  floor.material = 1;
  pile.walls = {cylinder, ramp, floor};
  pile.neighbour.body_broad_phase = true;
  auto sim = broad_phase_run(build_model(pile), "cpu");
  sim->advance(600);
  size_t parts = parts_missing_walls(*sim);
  INFO(parts << " of " << sim->model().parts.size() << " parts test fewer than all walls");
  CHECK(parts > sim->model().parts.size() / 2);
  check_broad_phase_keeps_bytes(pile, 1500, 50);
}

// Tubes like the cotton-stalk study's stalk (12 rings of 6 spheres of 1 mm, 24 x 8 mm: 6 parts)
// thrown together where a body's bounding sphere culls nothing and its parts' spheres cut close
// (a 0.2 mm skin): one falls across the ends of two side by side, one hits an end face, one falls
// on that one's far end, one stays apart; all on a floor. Every contact must stay in
// the list, while most sub-spheres (the tubes' far sides) skip the walk.
TEST_CASE("clumps: the broad phase by parts keeps the contacts at a long body's ends, and culls its far side") {
  CaseBuilder b;
  b.spec = clump_pile();  // its grain and steel, gravity and time step; not its particles and walls
  b.spec.bodies.clear();
  b.spec.spheres.clear();
  b.spec.templates.clear();
  b.spec.walls.clear();
  const int grain = 0, steel = 1;
  b.spec.neighbour.skin = 0.0002;
  std::vector<Sphere> tube;
  for (int layer = 0; layer < 12; ++layer)
    for (int k = 0; k < 6; ++k) {
      double a = kPi / 3 * k + (layer % 2 ? kPi / 6 : 0);
      tube.push_back({{-0.011 + 0.002 * layer, 0.003 * std::cos(a), 0.003 * std::sin(a)}, 0.001});
    }
  int t = b.clump_template("tube", tube);
  std::array<double, 4> along_y{std::sqrt(0.5), 0, 0, std::sqrt(0.5)};  // 90 degrees about z
  b.clump(t, {0, 0, 0.0045}, grain);                                               // 0: along x
  b.clump(t, {0.0105, 0, 0.0135}, grain, along_y, {0, 0, -0.3});                  // 1: across 0's end
  b.clump(t, {0.0255, 0, 0.0045}, grain, {1, 0, 0, 0}, {-0.3, 0, 0});             // 2: at 0's end face
  b.clump(t, {0, 0.0095, 0.0045}, grain, {1, 0, 0, 0}, {0, -0.3, 0});             // 3: alongside 0
  b.clump(t, {0.0355, 0, 0.0135}, grain, along_y, {0, 0, -0.3});                  // 4: on 2's far end
  b.clump(t, {0, 0.06, 0.0045}, grain, along_y);                                   // 5: apart
  b.plane({0, 0, 0.0005}, {0, 0, 1}, steel);
  CaseSpec spec = b.spec;
  spec.neighbour.body_broad_phase = true;
  auto sim = broad_phase_run(build_model(spec), "cpu");
  uint32_t n = sim->model().n_particles;
  std::set<std::pair<uint32_t, uint32_t>> touched;  // bodies whose sub-spheres have touched
  for (int batch = 0; batch < 48; ++batch) {
    sim->advance(25);
    HostState s = sim->state();
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t c = s.row_start[i]; c < s.row_start[i + 1]; ++c)
        if (s.partner[c] < n && s.history[c].w > 0) touched.insert({i / 72, s.partner[c] / 72});
  }
  for (const auto& [i, j] : touched) UNSCOPED_INFO("bodies " << i << " and " << j << " touched");
  CHECK(touched == std::set<std::pair<uint32_t, uint32_t>>{{0, 1}, {0, 2}, {0, 3}, {1, 3}, {2, 4}});
  size_t culled = culled_subs(*sim);
  INFO(culled << " of " << n << " sub-spheres skip the walk");
  CHECK(culled > n / 2);
  check_broad_phase_keeps_bytes(spec, 1200, 20);
}
