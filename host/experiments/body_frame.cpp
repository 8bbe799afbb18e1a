#include "experiments/body_frame.h"

#include <cmath>
#include <stdexcept>

#include "case/body_pose.h"

namespace repose {

namespace {

// (1/mass, position, velocity) of each free sphere or body.
template <class F>
void for_each_mass(const HostState& state, F&& f) {
  if (!state.bodies.empty()) {
    for (const auto& b : state.bodies) f(1.0 / b.pos.w, b.pos, b.vel);
    return;
  }
  for (size_t i = 0; i < state.pos.size(); ++i) f(1.0 / state.vel[i].w, state.pos[i], state.vel[i]);
}

}  // namespace

Vec3d body_centre(const HostState& state) {
  double mass = 0;
  Vec3d c{0, 0, 0};
  for_each_mass(state, [&](double m, const gpu::vec4& x, const gpu::vec4&) {
    mass += m;
    c[0] += m * x.x;
    c[1] += m * x.y;
    c[2] += m * x.z;
  });
  return {c[0] / mass, c[1] / mass, c[2] / mass};
}

double body_speed(const HostState& state) {
  double mass = 0;
  Vec3d p{0, 0, 0};
  for_each_mass(state, [&](double m, const gpu::vec4&, const gpu::vec4& v) {
    mass += m;
    p[0] += m * v.x;
    p[1] += m * v.y;
    p[2] += m * v.z;
  });
  return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / mass;
}

Vec3d first_body_spin(const HostState& state) {
  const gpu::vec4& w = state.bodies.empty() ? state.omega[0] : state.bodies[0].omega;
  return {w.x, w.y, w.z};
}

std::vector<SphereSpec> case_spheres(const CaseSpec& spec) {
  std::vector<SphereSpec> all = spec.spheres;
  for (const auto& body : spec.bodies) {
    auto subs = body_spheres(body, spec.templates.at(size_t(body.template_index)));
    all.insert(all.end(), subs.begin(), subs.end());
  }
  return all;
}

void shift_to_rest(CaseSpec& spec, const Vec3d& shift) {
  for (auto& s : spec.spheres) {
    for (int k = 0; k < 3; ++k) s.position[k] += shift[k];
    s.velocity = {0, 0, 0};
    s.angular_velocity = {0, 0, 0};
  }
  for (auto& b : spec.bodies) {
    for (int k = 0; k < 3; ++k) b.position[k] += shift[k];
    b.velocity = {0, 0, 0};
    b.angular_velocity = {0, 0, 0};
  }
}

size_t find_wall(const CaseSpec& spec, const std::string& name, const std::string& role) {
  for (size_t w = 0; w < spec.walls.size(); ++w)
    if (name.empty() || spec.walls[w].name == name) return w;
  throw std::runtime_error(spec.path + ": the experiment needs a [[wall]] as the " + role +
                           (name.empty() ? "" : " (named '" + name + "')"));
}

Interaction& interaction_between(CaseSpec& spec, int a, int b, const std::string& what) {
  for (auto& in : spec.interactions)
    if ((in.material_a == a && in.material_b == b) || (in.material_a == b && in.material_b == a)) return in;
  throw std::runtime_error(spec.path + ": no [[interaction]] between " + what);
}

}  // namespace repose
