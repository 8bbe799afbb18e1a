// Small helpers for engine tests: cases built in code, simulations on either backend, and
// byte comparison of states.
#pragma once
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <xmmintrin.h>

#include "case/case_spec.h"
#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"

namespace repose::test {

// A case without gravity, walls or particles; tests add what they need.
struct CaseBuilder {
  CaseSpec spec;
  CaseBuilder() {
    spec.path = "<test case>";
    spec.name = "test";
    spec.gravity = {0, 0, 0};
    spec.time.end_time = 1.0;
  }
  int material(double density, double shear_modulus, double poisson) {
    Material m;
    m.name = "m" + std::to_string(spec.materials.size());
    m.density = density;
    m.shear_modulus = shear_modulus;
    m.youngs_modulus = 2 * shear_modulus * (1 + poisson);
    m.poisson = poisson;
    spec.materials.push_back(m);
    return int(spec.materials.size()) - 1;
  }
  void interaction(int a, int b, double e, double mu, double mu_r) {
    Interaction in;
    in.material_a = a;
    in.material_b = b;
    in.restitution = e;
    in.static_friction = mu;
    in.rolling_friction = mu_r;
    spec.interactions.push_back(in);
  }
  int sphere(Vec3d pos, double radius, int mat, Vec3d vel = {0, 0, 0}, Vec3d omega = {0, 0, 0}) {
    SphereSpec s;
    s.position = pos;
    s.radius = radius;
    s.material = mat;
    s.velocity = vel;
    s.angular_velocity = omega;
    spec.spheres.push_back(s);
    return int(spec.spheres.size()) - 1;
  }
  int clump_template(const std::string& name, const std::vector<Sphere>& spheres) {
    TemplateSpec t;
    t.name = name;
    t.clump.name = name;
    t.clump.spheres = spheres;
    spec.templates.push_back(t);
    return int(spec.templates.size()) - 1;
  }
  int clump(int templ, Vec3d pos, int mat, std::array<double, 4> q = {1, 0, 0, 0},
            Vec3d vel = {0, 0, 0}, Vec3d omega = {0, 0, 0}) {
    BodySpec b;
    b.template_index = templ;
    b.material = mat;
    b.position = pos;
    b.orientation = q;
    b.velocity = vel;
    b.angular_velocity = omega;
    spec.bodies.push_back(b);
    return int(spec.bodies.size()) - 1;
  }
  void plane(Vec3d point, Vec3d normal, int mat) {
    WallSpec w;
    w.type = WallSpec::Type::Plane;
    w.point = point;
    w.normal = normal;
    w.material = mat;
    w.name = "plane" + std::to_string(spec.walls.size());
    spec.walls.push_back(w);
  }
  // A level square plate at the origin, the plate of the tilting tests.
  void level_plate(const std::string& name, double side, int mat) {
    WallSpec w;
    w.type = WallSpec::Type::Rectangle;
    w.name = name;
    w.point = {0, 0, 0};
    w.normal = {0, 0, 1};
    w.edge_axis = {1, 0, 0};
    w.size = {side, side};
    w.material = mat;
    spec.walls.push_back(w);
  }
  // Four spheres of radius r bonded in a square (the cabbage study's trick against rolling), resting
  // on z = 0.
  void four_sphere_body(double r, int mat) {
    int t = clump_template("four", {{{-r, -r, 0}, r}, {{r, -r, 0}, r}, {{-r, r, 0}, r}, {{r, r, 0}, r}});
    clump(t, {0, 0, r * 0.999}, mat);
  }
};

// n spheres of ~4 mm on a grid of `spacing` radii (jittered by `jitter` radii) above a floor
// and beside a side wall, moving and spinning at random: seeded, with particle and wall contacts.
inline CaseSpec seeded_cloud(uint32_t n, uint64_t seed, double spacing, double jitter) {
  CaseBuilder b;
  int grain = b.material(1000, 5e6, 0.3);
  int steel = b.material(7800, 8e10, 0.3);
  b.interaction(grain, grain, 0.5, 0.4, 0.05);
  b.interaction(grain, steel, 0.6, 0.3, 0.02);
  b.spec.gravity = {0, 0, -9.81};
  b.spec.time.rayleigh_fraction = 0.2;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const double r = 0.004;
  int side = 1;
  while (side * side * side < int(n)) ++side;
  for (uint32_t i = 0; i < n; ++i) {
    Vec3d p = {(i % side) * spacing * r + jitter * r * u(rng),
               ((i / side) % side) * spacing * r + jitter * r * u(rng),
               0.95 * r + (i / (side * side)) * spacing * r};
    b.sphere(p, r * (1 + 0.05 * u(rng)), grain, {0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)},
             {20 * u(rng), 20 * u(rng), 20 * u(rng)});
  }
  b.plane({0, 0, 0}, {0, 0, 1}, steel);
  b.plane({-r, 0, 0}, {1, 0, 0}, steel);
  return b.spec;
}

// Six two-sphere clumps resting on a floor with EPSD rolling springs (rolling springs and bodies
// in one state: the state file and restart tests).
inline CaseSpec epsd_clump_pairs() {
  CaseBuilder b;
  int m = b.material(1000, 5e6, 0.3);
  b.interaction(m, m, 0.5, 0.5, 0.05);
  b.spec.gravity = {0, 0, -9.81};
  b.spec.time.rayleigh_fraction = 0.2;
  b.spec.contact.rolling = RollingModel::ElasticPlastic;
  int t = b.clump_template("pair", {{{-0.004, 0, 0}, 0.005}, {{0.004, 0, 0}, 0.005}});
  for (int k = 0; k < 6; ++k) b.clump(t, {0.011 * k, 0, 0.0052}, m);
  b.plane({0, 0, 0}, {0, 0, 1}, m);
  return b.spec;
}

// An asymmetric clump: three spheres of different radii off one line, overlapping.
inline std::vector<Sphere> lumpy_clump() {
  return {{{0.0, 0.0, 0.0}, 0.010}, {{0.012, 0.003, 0.0}, 0.007}, {{-0.004, 0.011, 0.006}, 0.005}};
}

// 60 tumbling lumpy clumps and 20 spheres falling onto a floor beside a side wall.
inline CaseSpec clump_pile() {
  CaseBuilder b;
  int grain = b.material(1000, 5e6, 0.3);
  int steel = b.material(7800, 8e10, 0.3);
  b.interaction(grain, grain, 0.5, 0.5, 0.05);
  b.interaction(grain, steel, 0.6, 0.3, 0.02);
  b.spec.gravity = {0, 0, -9.81};
  int t = b.clump_template("lumpy", lumpy_clump());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 60; ++k) {
    std::array<double, 4> q{u(rng), u(rng), u(rng), u(rng)};
    double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= n;
    b.clump(t, {0.04 * (k % 4), 0.04 * ((k / 4) % 4), 0.02 + 0.04 * (k / 16)}, grain, q,
            {0.3 * u(rng), 0.3 * u(rng), -1.0}, {10 * u(rng), 10 * u(rng), 10 * u(rng)});
  }
  for (int k = 0; k < 20; ++k)
    b.sphere({0.02 + 0.04 * (k % 4), 0.02 + 0.04 * (k / 4 % 4), 0.2 + 0.03 * (k / 16)}, 0.006, grain);
  b.plane({0, 0, -0.012}, {0, 0, 1}, steel);
  b.plane({-0.02, 0, 0}, {1, 0, 0}, steel);
  b.spec.time.rayleigh_fraction = 0.2;
  return b.spec;
}

// The clump pile (two walls, bodies, EPSD springs stored per contact) with a wide skin and a
// rebuild every 25 steps: ~2000 contacts at the start, ~3300 after 1500 steps as it lands, so a
// list of 64 entries overflows when velocity Verlet evaluates F(0) and the grown list again
// near step 1000 (test_overflow_retry.cpp, test_particle_order.cpp).
inline CaseSpec wide_skin_pile(Integrator integrator = Integrator::VelocityVerlet) {
  CaseSpec spec = clump_pile();
  spec.contact.rolling = RollingModel::ElasticPlastic;
  spec.neighbour.skin = 0.04;
  spec.neighbour.rebuild_interval = 25;
  spec.integrator = integrator;
  return spec;
}

inline std::unique_ptr<Simulation> simulate(const CaseSpec& spec, const std::string& backend = "cpu",
                                            unsigned threads = 1, KernelVariant variant = {},
                                            uint32_t batch = 200) {
  return std::make_unique<Simulation>(build_model(spec),
                                      make_backend(backend, -1, threads, variant.workgroup), variant,
                                      batch);
}

// `spec` after `steps` steps on the CPU twin (2 threads, batches of 25) with the processor
// flushing denormal results to zero and reading denormal inputs as zero (MXCSR FTZ and DAZ, which
// the pool's threads inherit), as a GPU without shaderDenormPreserveFloat32 does (the NVIDIA
// H200: docs/engineering.md, "On hardware GPUs"). The same bytes as a run without it means that
// no denormal reaches the state.
inline std::unique_ptr<Simulation> simulate_flushing_denormals(const CaseSpec& spec, uint64_t steps) {
  struct FlushDenormals {  // FTZ and DAZ while in scope, then the processor's mode as it was
    unsigned saved = _mm_getcsr();
    FlushDenormals() { _mm_setcsr(saved | 0x8040u); }
    ~FlushDenormals() { _mm_setcsr(saved); }
  } flushing;
  auto sim = simulate(spec, "cpu", 2, {}, 25);
  sim->advance(steps);
  return sim;
}

// `spec` after `steps` steps (cpu, 2 threads) with the given neighbour skin and rebuild interval:
// the skin tests compare such runs, which may differ in no particle byte.
inline std::unique_ptr<Simulation> simulate_with_list(CaseSpec spec, double skin, int interval, uint64_t steps,
                                                      KernelVariant variant = {}, uint32_t batch = 200) {
  spec.neighbour.skin = skin;
  spec.neighbour.rebuild_interval = interval;
  auto sim = simulate(spec, "cpu", 2, variant, batch);
  sim->advance(steps);
  return sim;
}

inline double mass_of(const gpu::vec4& vel) { return 1.0 / double(vel.w); }

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Every array that carries state from step to step, compared byte for byte.
inline bool same_state(const HostState& a, const HostState& b, std::string* which = nullptr) {
  auto check = [&](bool ok, const char* name) {
    if (!ok && which && which->empty()) *which = name;
    return ok;
  };
  bool ok = true;
  ok &= check(same_bytes(a.pos, b.pos), "pos");
  ok &= check(same_bytes(a.vel, b.vel), "vel");
  ok &= check(same_bytes(a.omega, b.omega), "omega");
  ok &= check(same_bytes(a.force, b.force), "force");
  ok &= check(same_bytes(a.torque, b.torque), "torque");
  ok &= check(same_bytes(a.row_start, b.row_start), "row_start");
  ok &= check(same_bytes(a.partner, b.partner), "partner");
  ok &= check(same_bytes(a.history, b.history), "history");
  ok &= check(same_bytes(a.trans_list, b.trans_list), "trans_list");
  ok &= check(same_bytes(a.bodies, b.bodies), "bodies");
  ok &= check(same_bytes(a.rolling_spring, b.rolling_spring), "rolling_spring");
  return ok;
}

}  // namespace repose::test
