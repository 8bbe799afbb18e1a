// The body kernels in SIMD lanes (kernels_ref/body_lanes.cpp) against the scalar kernels they
// mirror (shaders/kernels/bodies.h): same bytes in every output, on every SIMD target, for
// bodies of 1 to 720 sub-spheres stored as runs of slots (cell order) or scrambled.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "body_lanes.h"
#include "contact_lanes.h"
#include "twin_kernels.h"

using namespace repose::gpu;

namespace {

// Random bodies (moving, turning, at any orientation) of mixed sizes, their sub-spheres in slots
// given by `runs` (each body's sub-spheres consecutive, bodies shuffled) or scrambled, and forces
// and torques on the sub-spheres (a third exactly zero, as for sub-spheres that touch nothing).
struct BodyScene {
  std::vector<Body> bodies;
  std::vector<SubSphere> subs;  // by slot
  std::vector<vec4> pos_at_build, force, torque;
  std::vector<uint> ids;
  uint n = 0;

  BodyScene(bool runs, uint64_t seed) {
    std::mt19937 rng{uint32_t(seed)};
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const uint sizes[] = {1, 3, 720, 40, 1, 17, 5, 203, 1, 2, 33, 64};
    std::vector<uint> body_of;
    for (uint b = 0; b < 45; ++b) {
      Body body{};
      uint count = sizes[b % 12];
      body.pos = vec4(0.2f * u(rng), 0.2f * u(rng), 0.5f + 0.2f * u(rng), 1.0f + u(rng));
      body.vel = vec4(u(rng), u(rng), u(rng), 0.0f);
      float q[4] = {u(rng), u(rng), u(rng), u(rng)};
      float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      body.quat = vec4(q[0] / len, q[1] / len, q[2] / len, q[3] / len);
      body.ang_mom = vec4(1e-6f * u(rng), 1e-6f * u(rng), 1e-6f * u(rng), 0.0f);
      body.omega = vec4(20.0f * u(rng), 20.0f * u(rng), 20.0f * u(rng), 0.0f);
      body.inv_inertia = vec4(1e4f * (1.5f + u(rng)), 1e4f * (1.5f + u(rng)), 1e4f * (1.5f + u(rng)), 0.0f);
      body.spheres = uvec4(n, count, 0u, 0u);
      bodies.push_back(body);
      for (uint k = 0; k < count; ++k) body_of.push_back(b);
      n += count;
    }
    std::vector<uint> order(bodies.size());  // bodies' runs in a shuffled order, or every slot shuffled
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), rng);
    for (uint b : order)
      for (uint k = 0; k < bodies[b].spheres.y; ++k) ids.push_back(bodies[b].spheres.x + k);
    if (!runs) std::shuffle(ids.begin(), ids.end(), rng);
    ids.resize(2 * n);
    for (uint s = 0; s < n; ++s) ids[n + ids[s]] = s;
    for (uint s = 0; s < n; ++s) {
      subs.push_back(SubSphere{vec4(0.04f * u(rng), 0.005f * u(rng), 0.005f * u(rng), 0.001f), uvec4(body_of[ids[s]], 0u, 0u, 0u)});
      pos_at_build.push_back(vec4(0.2f * u(rng), 0.2f * u(rng), 0.5f + 0.2f * u(rng), 0.0f));
      bool idle = s % 3u == 0u;
      force.push_back(idle ? vec4(0.0f) : vec4(u(rng), u(rng), u(rng), 0.0f));
      torque.push_back(idle ? vec4(0.0f) : vec4(1e-3f * u(rng), 1e-3f * u(rng), 1e-3f * u(rng), 0.0f));
    }
  }
};

// What the body kernels write.
struct BodyOutputs {
  std::vector<vec4> pos, vel, omega;
  std::vector<Body> bodies;
  std::vector<uint> control;
};

// body_place over every slot, then body_gather_kick over every body (both with `flags` and
// `kick`), in lanes or by the scalar kernels; `skin_sq`: the skin check's half skin, squared.
BodyOutputs run_bodies(const BodyScene& s, uint flags, float kick, float skin_sq, bool lanes) {
  BodyOutputs o;
  o.pos.assign(s.n, vec4(7.0f));
  o.vel.assign(s.n, vec4(7.0f));
  o.omega.assign(s.n, vec4(7.0f));
  o.bodies = s.bodies;
  o.control.assign(kControlWords, 0u);
  Kernels k;
  k.B_pos = o.pos.data();
  k.B_vel = o.vel.data();
  k.B_omega = o.omega.data();
  k.B_bodies = o.bodies.data();
  k.B_control = o.control.data();
  k.B_subs = const_cast<SubSphere*>(s.subs.data());
  k.B_pos_at_build = const_cast<vec4*>(s.pos_at_build.data());
  k.B_force = const_cast<vec4*>(s.force.data());
  k.B_torque = const_cast<vec4*>(s.torque.data());
  k.B_ids = const_cast<uint*>(s.ids.data());
  k.PC.n_particles = s.n;
  k.PC.n_bodies = uint(s.bodies.size());
  k.PC.flags = flags | kFlagBodies;
  k.PC.kick = kick;
  k.PC.dt = 1e-5f;
  k.PC.gz = -9.81f;
  k.PC.half_skin_sq = skin_sq;
  if (lanes) {
    body_place_lanes(k, 0, s.n);
    body_gather_kick_lanes(k, 0, s.bodies.size());
  } else {
    for (uint i = 0; i < s.n; ++i) k.k_body_place(i);
    for (uint b = 0; b < s.bodies.size(); ++b) k.k_body_gather_kick(b);
  }
  return o;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("body kernels in SIMD lanes: the scalar kernels' bytes on every SIMD target", "[engine][bitexact]") {
  BodyScene runs(true, 5), scrambled(false, 6);
  for (int64_t target : contact_lanes_targets()) {
    pin_contact_lanes_target(target);
    for (const BodyScene* s : {&runs, &scrambled})
      for (uint flags : {0u, kFlagDrift})
        for (float kick : {0.0f, 0.5f})
          for (float skin_sq : {1e6f, 1e-12f}) {  // no sub-sphere past half the skin, or some
            BodyOutputs scalar = run_bodies(*s, flags, kick, skin_sq, false);
            BodyOutputs lanes = run_bodies(*s, flags, kick, skin_sq, true);
            INFO("flags " << flags << ", kick " << kick << ", skin^2 " << skin_sq << ", runs " << (s == &runs)
                          << ", lanes on " << contact_lanes_target());
            CHECK(same_bytes(scalar.pos, lanes.pos));
            CHECK(same_bytes(scalar.vel, lanes.vel));
            CHECK(same_bytes(scalar.omega, lanes.omega));
            CHECK(same_bytes(scalar.bodies, lanes.bodies));
            CHECK(same_bytes(scalar.control, lanes.control));
            CHECK(scalar.control[kCtlNeedRebuild] == ((flags & kFlagDrift) && skin_sq < 1.0f ? 1u : 0u));
          }
  }
  pin_contact_lanes_target(0);
}
