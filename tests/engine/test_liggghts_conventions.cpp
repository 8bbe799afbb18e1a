// The LIGGGHTS conventions Repose offers, checked against LIGGGHTS-PUBLIC's own formulas written
// out here in double: the cdt rolling torque (rolling_model_cdt.h) and the sjkr cohesion area
// (cohesion_model_sjkr.h). The kernel functions are called directly on the CPU twin's kernel struct
// (they are stateless: it needs no buffers), then a sphere spinning about the contact normal shows
// the twist left out in a simulation.
#include <catch2/catch.hpp>

#include "engine_test_support.h"
#include "twin_kernels.h"

using namespace repose;
using namespace repose::test;

namespace {

using D3 = std::array<double, 3>;
using ContactOut = gpu::Kernels::ContactOut;
using ContactGeometry = gpu::Kernels::ContactGeometry;
gpu::Kernels kernels;

D3 d3(const gpu::vec3& v) { return {v.x, v.y, v.z}; }

// A sphere pair (or a sphere on a wall) pressed together, spinning: the full contact entry.
ContactOut contact(bool wall, uint32_t flags, gpu::vec3 w_i, gpu::vec3 w_j, ContactGeometry& g,
                   gpu::PairParams& pp) {
  CaseBuilder b;
  int m = b.material(1000, 1e7, 0.3);
  pp = pair_params(b.spec.materials[0], b.spec.materials[0], {0, 0, 0.3, 0.5, 0.05});
  g.n = gpu::vec3(0.6f, 0.0f, 0.8f);
  g.overlap = 2e-4f;
  float r1 = 0.01f, r2 = wall ? 0.0f : 0.015f;
  g.radius_star = wall ? r1 : r1 * r2 / (r1 + r2);
  g.mass_star = 0.003f;
  g.ri = r1 - 0.5f * g.overlap;
  g.rj = wall ? 0.0f : r2 - 0.5f * g.overlap;
  g.lever_i = g.ri;
  g.lever_j = g.rj;
  g.cohesion_lens = -1.0f;
  gpu::vec3 shear(0.0f);
  (void)m;
  // process_contact passes a wall's spin as zero: LIGGGHTS's torques ignore it.
  gpu::vec3 w_other = wall ? gpu::vec3(0.0f) : w_j;
  return kernels.hertz_mindlin(g, gpu::vec3(0.1f, -0.05f, -0.3f), w_i, w_other, wall, pp, 1e-6f, flags, shear);
}

}  // namespace

TEST_CASE("rolling_omega relative is LIGGGHTS cdt: mu_r kn dn R* (w - (w.n) n) / |w|, twist in |w| only",
          "[engine][liggghts]") {
  const uint32_t flags = gpu::kFlagRollingConstTorque | gpu::kFlagRollingRelativeOmega;
  gpu::vec3 w_i(30.0f, -12.0f, 25.0f), w_j(-4.0f, 8.0f, 2.0f);
  for (bool wall : {false, true}) {
    ContactGeometry g;
    gpu::PairParams pp;
    ContactOut o = contact(wall, flags, w_i, w_j, g, pp);
    // LIGGGHTS: kn dn is the Hertz elastic force 4/3 E* sqrt(R* dn) dn; the lever R* for two
    // spheres, the contact radius r - dn/2 against a wall, whose spin is not counted.
    double dn = g.overlap, e_star = pp.e_star, mu_r = pp.rolling_friction;
    double fn_el = 4.0 / 3.0 * e_star * std::sqrt(double(g.radius_star) * dn) * dn;
    double lever = wall ? double(g.ri) : double(g.radius_star);
    D3 w = wall ? d3(w_i) : D3{w_i.x - w_j.x, w_i.y - w_j.y, w_i.z - w_j.z};
    D3 n = d3(g.n);
    double lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    D3 t{};
    for (int k = 0; k < 3; ++k) t[k] = -mu_r * fn_el * lever * w[k] / lw;
    double tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    for (int k = 0; k < 3; ++k) t[k] -= tn * n[k];
    // The tangential force's moment is the same in either convention: take it out.
    D3 moment = {-g.ri * o.n_x_ft.x, -g.ri * o.n_x_ft.y, -g.ri * o.n_x_ft.z};
    D3 rolling_i = {o.torque_i.x - moment[0], o.torque_i.y - moment[1], o.torque_i.z - moment[2]};
    INFO((wall ? "wall" : "pair") << ": torque (" << rolling_i[0] << ", " << rolling_i[1] << ", " << rolling_i[2]
                                  << ") vs LIGGGHTS (" << t[0] << ", " << t[1] << ", " << t[2] << ")");
    double scale = mu_r * fn_el * lever;
    for (int k = 0; k < 3; ++k) CHECK(rolling_i[k] == Approx(t[k]).margin(1e-5 * scale));  // float rounding
    if (!wall) {
      D3 moment_j = {-g.rj * o.n_x_ft.x, -g.rj * o.n_x_ft.y, -g.rj * o.n_x_ft.z};
      for (int k = 0; k < 3; ++k)
        CHECK(double((&o.torque_j.x)[k]) - moment_j[k] == Approx(-t[k]).margin(1e-5 * scale));
    }
  }
}

TEST_CASE("cohesion_area intersection is LIGGGHTS sjkr's disc, about twice EDEM's pi R* dn", "[engine][liggghts]") {
  const double pi_k = kPi * 2.0e5;  // k = 2e5 J/m^3
  for (double dn : {1e-5, 1e-4, 1e-3}) {
    double r1 = 0.01, r2 = 0.015, d = r1 + r2 - dn;
    // sjkr: A = -pi/4 (d-r1-r2)(d+r1-r2)(d-r1+r2)(d+r1+r2) / d^2; a wall: pi (r^2 - (r - dn)^2).
    double a_pair = -kPi / 4 * (d - r1 - r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2) / (d * d);
    double a_wall = kPi * (r1 * r1 - (r1 - dn) * (r1 - dn));
    float lens_pair = kernels.cohesion_intersection_area(float(r1), float(r2), float(d), float(dn), false);
    float lens_wall = kernels.cohesion_intersection_area(float(r1), 0.0f, 0.0f, float(dn), true);
    double f_pair = kernels.linear_cohesion(float(pi_k), 0.0f, float(dn), lens_pair);
    double f_wall = kernels.linear_cohesion(float(pi_k), 0.0f, float(dn), lens_wall);
    INFO("dn = " << dn);
    // Float inputs: d carries ~1e-7 relative error, and (d+r1-r2) etc. no cancellation.
    CHECK(f_pair == Approx(pi_k / kPi * a_pair).epsilon(1e-5));
    CHECK(f_wall == Approx(pi_k / kPi * a_wall).epsilon(1e-5));
    double r_star = r1 * r2 / (r1 + r2);
    double edem = kernels.linear_cohesion(float(pi_k), float(r_star), float(dn), -1.0f);
    CHECK(edem == Approx(pi_k * r_star * dn).epsilon(1e-6));
    if (dn <= 1e-4) CHECK(f_pair / edem == Approx(2.0).epsilon(0.01));  // 2 R* dn - O(dn^2)
  }
}

// A sphere on a plate spinning only about the vertical (the contact normal): EDEM's torque
// opposes the spin (mu_r |Fn| R against w), LIGGGHTS cdt's has no component along n at all.
TEST_CASE("a sphere spinning about the contact normal: EDEM's rolling torque slows it, LIGGGHTS cdt's does not",
          "[engine][liggghts]") {
  auto spin_after = [](RollingOmega omega, double seconds, double& expected_rate) {
    CaseBuilder b;
    int g = b.material(1000, 1e7, 0.3);
    int floor = b.material(7800, 8e10, 0.3);
    const double R = 0.01, mu_r = 0.05, w0 = 50;
    b.interaction(g, g, 0.5, 0.5, mu_r);
    b.interaction(g, floor, 0.5, 0.5, mu_r);
    b.spec.gravity = {0, 0, -9.81};
    b.spec.time.rayleigh_fraction = 0.2;
    b.spec.contact.rolling_omega = omega;
    b.spec.contact.rolling_lever = RollingLever::Sphere;
    double m = 1000 * 4.0 / 3.0 * kPi * R * R * R;
    double E = 2e7 * 1.3, E_star = 1 / ((1 - 0.09) / E + (1 - 0.09) / (2 * 8e10 * 1.3));
    double d = std::pow(m * 9.81 / (4.0 / 3.0 * E_star * std::sqrt(R)), 2.0 / 3.0);
    b.sphere({0, 0, R - d}, R, g, {0, 0, 0}, {0, 0, w0});
    b.plane({0, 0, 0}, {0, 0, 1}, floor);
    expected_rate = mu_r * m * 9.81 * (R - d / 2) / (0.4 * m * R * R);  // EDEM: T / I
    auto sim = simulate(b.spec);
    sim->advance(uint64_t(seconds / sim->model().dt));
    return double(sim->state().omega[0].z);
  };
  double rate = 0, t = 0.05;
  double edem = spin_after(RollingOmega::Own, t, rate);
  double cdt = spin_after(RollingOmega::Relative, t, rate);
  INFO("EDEM " << edem << " rad/s (theory " << 50 - rate * t << "), LIGGGHTS cdt " << cdt);
  CHECK(edem == Approx(50 - rate * t).epsilon(0.01));  // the static overlap settles in the first steps
  CHECK(cdt == 50.0);  // no twisting torque, to the bit
}
