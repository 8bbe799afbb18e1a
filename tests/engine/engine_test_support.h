// Small helpers for engine tests: cases built in code, simulations on either backend, and
// byte comparison of states.
#pragma once
#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include "case/case_spec.h"
#include "engine/backend_factory.h"
#include "engine/model.h"
#include "engine/simulation.h"

namespace repose::test {

constexpr double kPi = 3.14159265358979323846;

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
  void plane(Vec3d point, Vec3d normal, int mat) {
    WallSpec w;
    w.type = WallSpec::Type::Plane;
    w.point = point;
    w.normal = normal;
    w.material = mat;
    w.name = "plane" + std::to_string(spec.walls.size());
    spec.walls.push_back(w);
  }
};

inline std::unique_ptr<Simulation> simulate(const CaseSpec& spec, const std::string& backend = "cpu",
                                            unsigned threads = 1, KernelVariant variant = {},
                                            uint32_t batch = 200) {
  return std::make_unique<Simulation>(build_model(spec),
                                      make_backend(backend, -1, threads, variant.workgroup), variant,
                                      batch);
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
  return ok;
}

}  // namespace repose::test
