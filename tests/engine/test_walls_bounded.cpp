// Rectangle and triangle-mesh walls: face, edge and corner contacts push along the normal from
// the closest point with Hertz's force, and a mesh counts each touching point once (walls.h).
#include <catch2/catch.hpp>

#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

struct Rig {
  CaseBuilder b;
  int grain, steel;
  Rig() {
    grain = b.material(1000, 1e7, 0.3);
    steel = b.material(7800, 8e10, 0.3);
    b.interaction(grain, steel, 0.5, 0.5, 0.0);
    b.interaction(grain, grain, 0.5, 0.5, 0.0);
    b.spec.time.rayleigh_fraction = 0.2;
  }
  void rectangle(Vec3d centre, Vec3d normal, Vec3d edge_axis, double a, double b_) {
    WallSpec w;
    w.type = WallSpec::Type::Rectangle;
    w.point = centre;
    w.normal = normal;
    w.edge_axis = edge_axis;
    w.size = {a, b_};
    w.material = steel;
    w.name = "rect" + std::to_string(b.spec.walls.size());
    b.spec.walls.push_back(w);
  }
  void cylinder(Vec3d base, double radius, double height) {
    WallSpec w;
    w.type = WallSpec::Type::Cylinder;
    w.base = base;
    w.axis = {0, 0, 1};
    w.radius = radius;
    w.height = height;
    w.material = steel;
    w.name = "cylinder";
    b.spec.walls.push_back(w);
  }
  void mesh(std::vector<Vec3d> vertices, std::vector<std::array<uint32_t, 3>> triangles) {
    auto m = std::make_shared<WallMesh>();
    m->vertices = std::move(vertices);
    m->triangles = std::move(triangles);
    WallSpec w;
    w.type = WallSpec::Type::Mesh;
    w.mesh = m;
    w.material = steel;
    w.name = "mesh" + std::to_string(b.spec.walls.size());
    b.spec.walls.push_back(w);
  }
};

constexpr double R = 0.01, kDelta = 1e-4;

// Hertz force of the sphere pressed kDelta into a wall (float E* as the kernels use it).
double hertz(const Rig& rig) {
  auto p = pair_params(rig.b.spec.materials[rig.grain], rig.b.spec.materials[rig.steel], {});
  return 4.0 / 3.0 * double(p.e_star) * std::sqrt(R) * kDelta * std::sqrt(kDelta);
}

// Total force of a sphere at rest at `x` on all walls, from the initial force evaluation.
Vec3d wall_force(Rig& rig, Vec3d x) {
  rig.b.sphere(x, R, rig.grain);
  auto sim = simulate(rig.b.spec);
  Vec3d f{0, 0, 0};
  for (const auto& w : sim->wall_forces()) f = {f[0] + w.fx, f[1] + w.fy, f[2] + w.fz};
  return f;
}

Vec3d along(Vec3d q, Vec3d dir, double distance) {
  double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  return {q[0] + dir[0] / n * distance, q[1] + dir[1] / n * distance, q[2] + dir[2] / n * distance};
}

// The force on the wall must be F pointing against `dir` (the normal from the wall to the sphere).
void check_push(Vec3d f, Vec3d dir, double magnitude) {
  double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  INFO("force on the wall (" << f[0] << ", " << f[1] << ", " << f[2] << "), expected " << magnitude
                             << " against (" << dir[0] << ", " << dir[1] << ", " << dir[2] << ")");
  // float positions and overlaps of 1e-4 m at 1e-2 m: the overlap carries ~1e-5 relative error.
  for (int k = 0; k < 3; ++k) CHECK(f[k] == Approx(-magnitude * dir[k] / n).margin(1e-4 * magnitude));
}

// Two triangles over the square [-a, a]^2 at z = 0, sharing the diagonal from (-a,-a) to (a,a).
void square_plate(Rig& rig, double a) {
  rig.mesh({{-a, -a, 0}, {a, -a, 0}, {a, a, 0}, {-a, a, 0}}, {{0, 1, 2}, {0, 2, 3}});
}

}  // namespace

TEST_CASE("rectangle wall: face, edge and corner contacts along the closest-point normal", "[walls]") {
  auto make = [] {
    Rig rig;
    rig.rectangle({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.2, 0.1);  // half extents 0.1 (x) and 0.05 (y)
    return rig;
  };
  {
    Rig rig = make();
    double F = hertz(rig);
    check_push(wall_force(rig, {0.02, 0.01, R - kDelta}), {0, 0, 1}, F);
  }
  {
    Rig rig = make();
    double F = hertz(rig);
    check_push(wall_force(rig, along({0.1, 0.0, 0}, {1, 0, 1}, R - kDelta)), {1, 0, 1}, F);
  }
  {
    Rig rig = make();
    double F = hertz(rig);
    check_push(wall_force(rig, along({0.1, 0.05, 0}, {1, 1, 1}, R - kDelta)), {1, 1, 1}, F);
  }
  {
    // One-sided: an edge seen from behind the plate does not touch.
    Rig rig = make();
    check_push(wall_force(rig, along({-0.1, 0.0, 0}, {-1, 0, -1}, R - kDelta)), {0, 0, 1}, 0.0);
  }
}

// The bottomless cylinder holds the spheres inside it. A sphere outside, near or far, is not its
// business (the lifted-cylinder rigs leave spheres outside once the cylinder rises).
TEST_CASE("cylinder wall: a sphere inside is pushed by Hertz's force, one outside feels nothing", "[walls]") {
  auto make = [] {
    Rig rig;
    rig.cylinder({0, 0, -0.5}, 0.12, 1.0);
    return rig;
  };
  {
    Rig rig = make();  // inside, pressed kDelta into the surface along (1, 1, 0)
    double F = hertz(rig);
    check_push(wall_force(rig, along({0, 0, 0}, {1, 1, 0}, 0.12 - R + kDelta)), {-1, -1, 0}, F);
  }
  for (double d : {0.12 + R - kDelta, 0.12 + kDelta, 0.18}) {
    Rig rig = make();  // outside: touching the outer surface, centre just outside, far away
    INFO("centre " << d << " m from the axis");
    check_push(wall_force(rig, along({0, 0, 0}, {1, 0, 0}, d)), {1, 0, 0}, 0.0);
  }
  // Without gravity, a sphere at rest 0.18 m from the axis stays at rest (it used to gain ~1 J
  // in 0.01 s from a contact with the far side of the inner surface).
  Rig rig = make();
  rig.b.sphere({0.18, 0, 0}, R, rig.grain);
  auto sim = simulate(rig.b.spec);
  sim->advance(uint64_t(0.01 / sim->model().dt) + 1);
  CHECK(sim->contacts() == 0);
  CHECK(sim->kinetic_energy().translational == 0.0);
}

TEST_CASE("mesh wall: face, boundary edge and corner contacts of a two-triangle plate, each once", "[walls]") {
  const double a = 0.05;
  struct Case { const char* what; Vec3d q, dir; };
  const Case cases[] = {
      {"face of triangle 0", {0.02, -0.01, 0}, {0, 0, 1}},
      {"face of triangle 1", {-0.02, 0.01, 0}, {0, 0, 1}},
      {"on the shared diagonal", {0.01, 0.01, 0}, {0, 0, 1}},
      {"boundary edge x = a", {a, 0.0, 0}, {1, 0, 1}},
      {"shared corner (-a, -a)", {-a, -a, 0}, {-1, -1, 1}},
      {"unshared corner (a, -a)", {a, -a, 0}, {1, -1, 1}},
      // Beyond edge x = -a of triangle 1, next to the shared corner: triangle 0 sees its vertex.
      {"edge next to a shared corner", {-a, -a + 0.002, 0}, {-1, 0, 0.3}},
      {"below the plate (two-sided)", {0.02, -0.01, 0}, {0, 0, -1}},
  };
  for (const Case& c : cases) {
    Rig rig;
    square_plate(rig, a);
    double F = hertz(rig);
    INFO(c.what);
    check_push(wall_force(rig, along(c.q, c.dir, R - kDelta)), c.dir, F);
  }
}

TEST_CASE("mesh wall: a ridge keeps one edge contact, and no edge contact beside a face", "[walls]") {
  // A roof along y: triangles sloping down at 30 degrees to either side of the ridge x = 0.
  const double a = 0.05, s = a * std::tan(30.0 * kPi / 180.0);
  auto roof = [&](Rig& rig) {
    rig.mesh({{0, -a, 0}, {0, a, 0}, {-a, 0, -s}, {a, 0, -s}}, {{0, 1, 2}, {1, 0, 3}});
  };
  {
    Rig rig;
    roof(rig);
    check_push(wall_force(rig, {0, 0, R - kDelta}), {0, 0, 1}, hertz(rig));
  }
  {
    // Over the face of the +x triangle near the ridge: its face alone, along its normal.
    Rig rig;
    roof(rig);
    Vec3d n = {std::sin(30.0 * kPi / 180.0), 0, std::cos(30.0 * kPi / 180.0)};
    Vec3d q = {0.003 * std::cos(30.0 * kPi / 180.0), 0.0, -0.003 * std::sin(30.0 * kPi / 180.0)};
    check_push(wall_force(rig, along(q, n, R - kDelta)), n, hertz(rig));
  }
}

TEST_CASE("sphere rolling across the shared edge of a flat two-triangle plate: the normal force is the plane's",
          "[walls]") {
  // The same sphere rolls on a plane and on the plate (diagonal crossed at x = y); a double
  // counted or dropped contact at the diagonal would double or zero the normal force.
  auto run = [](bool plate) {
    Rig rig;
    rig.b.spec.gravity = {0, 0, -9.81};
    if (plate) square_plate(rig, 0.05);
    else rig.b.plane({0, 0, 0}, {0, 0, 1}, rig.steel);
    double v = 0.2;
    rig.b.sphere({-0.02, 0.005, R - 2e-6}, R, rig.grain, {v, 0, 0}, {0, v / R, 0});
    auto sim = simulate(rig.b.spec);
    std::vector<double> fz;
    std::vector<double> x;
    while (sim->state().pos[0].x < 0.03) {
      sim->advance(5);
      double f = 0;
      for (const auto& w : sim->wall_forces()) f += w.fz;
      fz.push_back(f);
      x.push_back(sim->state().pos[0].x);
    }
    return std::make_pair(fz, x);
  };
  auto [on_plane, x_plane] = run(false);
  auto [on_plate, x_plate] = run(true);
  REQUIRE(on_plane.size() == on_plate.size());
  double m = 1000 * 4.0 / 3.0 * kPi * R * R * R, mean = 0;
  bool crossed = false;
  for (size_t k = 0; k < on_plane.size(); ++k) {
    INFO("sample " << k << " at x = " << x_plate[k] << ": plate " << on_plate[k] << " N, plane " << on_plane[k] << " N");
    REQUIRE(std::abs(on_plate[k] - on_plane[k]) <= 1e-6 * std::abs(on_plane[k]));
    crossed = crossed || x_plate[k] > 0.005;  // the diagonal at y = 0.005
    mean += -on_plane[k] / double(on_plane.size());
  }
  CHECK(crossed);
  // Averaged over the run the plane carries the weight (the settling bounce is small: 2 um drop).
  CHECK(mean == Approx(m * 9.81).epsilon(0.02));
}

TEST_CASE("a lifted cylinder and a tilting rectangle move exactly as prescribed", "[walls]") {
  Rig rig;
  WallSpec cyl;
  cyl.type = WallSpec::Type::Cylinder;
  cyl.base = {0.1, -0.2, 0.0};
  cyl.axis = {0, 0, 1};
  cyl.radius = 0.3;
  cyl.height = 1.0;
  cyl.material = rig.steel;
  cyl.name = "cylinder";
  cyl.motion.velocity = {0, 0, 0.05};
  cyl.motion.start_time = 1.0;
  rig.b.spec.walls.push_back(cyl);
  rig.rectangle({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.4, 0.4);
  rig.b.spec.walls.back().motion.rotation_axis = {0, 1, 0};
  rig.b.spec.walls.back().motion.angular_rate = kPi / 180;  // 1 degree per second
  rig.b.sphere({0, 0, 0.5}, R, rig.grain);
  Model model = build_model(rig.b.spec);
  for (double t : {0.0, 0.5, 1.0, 1.25, 3.0, 10.0, 21.0}) {
    INFO("t = " << t);
    auto s = model.wall_state(0, t);
    double lifted = 0.05 * std::max(0.0, t - 1.0);
    CHECK(s.p0.x == float(0.1));
    CHECK(s.p0.y == float(-0.2));
    CHECK(s.p0.z == float(lifted));
    CHECK(s.vel.z == float(t >= 1.0 ? 0.05 : 0.0));
    CHECK(s.p1.w == float(0.3));
    CHECK(s.vel.w == float(1.0));
    auto plate = model.wall_state(1, t);
    double angle = kPi / 180 * t;
    CHECK(plate.p1.x == float(std::sin(angle)));
    CHECK(plate.p1.z == float(std::cos(angle)));
    CHECK(plate.omega.y == float(kPi / 180));
  }
  // And the simulation uploads those states: a sphere resting in the lifting cylinder's way is
  // not touched before the lift (walls never move the particles' own positions).
  auto sim = simulate(rig.b.spec);
  sim->advance(10);
  CHECK(sim->state().pos[0].x == 0.0f);
}

TEST_CASE("rectangle and mesh walls in motion: lavapipe and the CPU twin give identical bytes", "[walls]") {
  Rig rig;
  rig.b.spec.gravity = {0, 0, -9.81};
  rig.rectangle({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.1, 0.1);
  rig.b.spec.walls.back().motion.rotation_axis = {1, 1, 0};
  rig.b.spec.walls.back().motion.angular_rate = 0.5;
  const double a = 0.05, h = 0.04;
  rig.mesh({{-a, -a, h}, {a, -a, h}, {a, a, h + 0.02}, {-a, a, h + 0.02}, {0, 0, h - 0.02}},
           {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});  // a shallow funnel above the plate
  rig.b.spec.walls.back().motion.velocity = {0, 0, 0.3};
  rig.b.spec.walls.back().motion.start_time = 0.005;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 150; ++i)
    rig.b.sphere({0.035 * u(rng), 0.035 * u(rng), h + 0.01 + 0.05 * (i / 150.0) + 0.002 * u(rng)}, 0.003, rig.grain,
                 {0.1 * u(rng), 0.1 * u(rng), -0.5});
  auto cpu = simulate(rig.b.spec, "cpu", 2);
  auto gpu = simulate(rig.b.spec, "vulkan");
  cpu->advance(600);
  gpu->advance(600);
  std::string which;
  bool same = same_state(cpu->state(), gpu->state(), &which);
  INFO("differ in " << which);
  CHECK(same);
  CHECK(cpu->contacts() > 0);
  auto fc = cpu->wall_forces(), fg = gpu->wall_forces();
  REQUIRE(fc.size() == fg.size());
  for (size_t k = 0; k < fc.size(); ++k) CHECK(fc[k].fz == fg[k].fz);
}

// The neighbour list must hold every wall a sphere can touch before the next rebuild: a sphere
// just beyond a rectangle's edge and behind its plane (where the edge test does not reach) that
// slides over the face touches it there, and one behind the plane rising past the edge touches
// the edge. With a wide skin the list is not rebuilt before that
// happens, with a narrow one it is; the bytes must not differ (the list once lost this contact).
// The same for a sphere behind a plane and just outside a cylinder.
TEST_CASE("walls: a sphere behind a rectangle's plane sliding over its face, the same bytes for any skin", "[walls]") {
  auto run = [](double skin, int wall) {
    Rig rig;
    rig.b.spec.gravity = {0, 0, 0};
    if (wall == 0) {
      rig.rectangle({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.1, 0.1);  // half extents 0.05
      rig.b.sphere({0.052, 0, -0.002}, R * 0.5, rig.grain, {-0.5, 0, 0});
    } else if (wall == 1) {
      // Beyond the edge and behind the plane, rising in front of it: an edge contact.
      rig.rectangle({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.1, 0.1);
      rig.b.sphere({0.053, 0, -0.001}, R * 0.5, rig.grain, {0, 0, 0.5});
    } else {
      rig.cylinder({0, 0, 0}, 0.05, 0.1);
      rig.b.sphere({0.052, 0, 0.05}, R * 0.5, rig.grain, {-0.5, 0, 0});
    }
    rig.b.spec.neighbour.skin = skin;
    auto sim = simulate(rig.b.spec);
    sim->advance(3000);
    return sim->state();
  };
  for (int wall : {0, 1, 2}) {
    INFO((wall == 0 ? "rectangle face" : wall == 1 ? "rectangle edge" : "cylinder"));
    HostState narrow = run(0.0005, wall), wide = run(0.02, wall);
    const Vec3d v0 = wall == 1 ? Vec3d{0, 0, 0.5} : Vec3d{-0.5, 0, 0};  // its start velocity
    CHECK((narrow.vel[0].x != float(v0[0]) || narrow.vel[0].z != float(v0[2])));  // it met the wall
    CHECK(same_bytes(narrow.pos, wide.pos));
    CHECK(same_bytes(narrow.vel, wide.vel));
  }
}
