// kick_drift and gather_kick's kick in SIMD lanes (kernels_ref/kick_lanes.cpp) against the scalar
// kernels they mirror (shaders/kernels/integrate.h, kick.h): same bytes in every output, on every
// SIMD target, with fixed particles among moving ones, air drag on and off, drifting or not, a
// particle past half the skin or none, and a tail shorter than the lanes.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <vector>

#include "contact_lanes.h"
#include "kick_lanes.h"
#include "twin_kernels.h"

using namespace repose::gpu;

namespace {

// Random particles (every fifth fixed: inverse mass 0) and a contact list: each particle owns 0-4
// entries with random partners (every 37th owns 12, all with the next particle, whose transposed
// row is then as long), their transposed rows built as the neighbour list builds them.
struct KickScene {
  uint n = 16 * 9 + 7;
  std::vector<vec4> pos, vel, omega, pos_at_build, force, torque, contact_force, torque_i, torque_j;
  std::vector<uint> row_start, trans_start, trans_list;

  explicit KickScene(uint64_t seed) {
    std::mt19937 rng{uint32_t(seed)};
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (uint i = 0; i < n; ++i) {
      pos.push_back(vec4(0.1f * u(rng), 0.1f * u(rng), 0.1f * u(rng), 0.005f + 0.004f * u(rng)));
      vel.push_back(vec4(u(rng), u(rng), u(rng), i % 5u == 0u ? 0.0f : 1e3f * (1.5f + u(rng))));
      omega.push_back(vec4(50.0f * u(rng), 50.0f * u(rng), 50.0f * u(rng), 1e7f * (1.5f + u(rng))));
      pos_at_build.push_back(pos.back() + vec4(1e-5f * u(rng), 1e-5f * u(rng), 1e-5f * u(rng), 0.0f));
      force.push_back(vec4(u(rng), u(rng), u(rng), 0.0f));
      torque.push_back(vec4(1e-4f * u(rng), 1e-4f * u(rng), 1e-4f * u(rng), 0.0f));
    }
    std::vector<uint> owner;
    std::vector<std::vector<uint>> as_partner(n);
    row_start.push_back(0u);
    for (uint i = 0; i < n; ++i) {
      const bool long_rows = i % 37u == 3u;
      for (uint e = long_rows ? 12u : rng() % 5u; e > 0; --e) {
        as_partner[long_rows ? (i + 1u) % n : rng() % n].push_back(uint(owner.size()));
        owner.push_back(i);
        contact_force.push_back(vec4(u(rng), u(rng), u(rng), 0.5f));
        torque_i.push_back(vec4(1e-4f * u(rng), 1e-4f * u(rng), 1e-4f * u(rng), 0.0f));
        torque_j.push_back(vec4(1e-4f * u(rng), 1e-4f * u(rng), 1e-4f * u(rng), 0.0f));
      }
      row_start.push_back(uint(owner.size()));
    }
    trans_start.push_back(0u);
    for (uint i = 0; i < n; ++i) {
      trans_list.insert(trans_list.end(), as_partner[i].begin(), as_partner[i].end());
      trans_start.push_back(uint(trans_list.size()));
    }
  }
};

struct KickOutputs {
  std::vector<vec4> pos, vel, omega, force, torque;
  std::vector<uint> control;
};

enum class Pass { KickDrift, GatherKick };

// One pass over every particle, in lanes or by the scalar kernel.
KickOutputs run_pass(const KickScene& s, Pass pass, uint flags, float kick, float air_drag, float skin_sq, bool lanes) {
  KickOutputs o{s.pos, s.vel, s.omega, s.force, s.torque, std::vector<uint>(kControlWords, 0u)};
  o.control[kCtlContacts] = s.row_start.back();
  Kernels k;
  k.B_pos = o.pos.data();
  k.B_vel = o.vel.data();
  k.B_omega = o.omega.data();
  k.B_force = o.force.data();
  k.B_torque = o.torque.data();
  k.B_control = o.control.data();
  k.B_pos_at_build = const_cast<vec4*>(s.pos_at_build.data());
  k.B_contact_force = const_cast<vec4*>(s.contact_force.data());
  k.B_torque_i = const_cast<vec4*>(s.torque_i.data());
  k.B_torque_j = const_cast<vec4*>(s.torque_j.data());
  k.B_row_start = const_cast<uint*>(s.row_start.data());
  k.B_trans_start = const_cast<uint*>(s.trans_start.data());
  k.B_trans_list = const_cast<uint*>(s.trans_list.data());
  k.PC.n_particles = s.n;
  k.PC.flags = flags;
  k.PC.kick = kick;
  k.PC.air_drag = air_drag;
  k.PC.dt = 1e-4f;
  k.PC.gx = 0.5f;
  k.PC.gz = -9.81f;
  k.PC.half_skin_sq = skin_sq;
  if (lanes)
    (pass == Pass::KickDrift ? kick_drift_lanes : gather_kick_lanes)(k, 0, s.n + 5);  // past n: as a workgroup's
  else
    for (uint i = 0; i < s.n; ++i) pass == Pass::KickDrift ? k.k_kick_drift(i) : k.k_gather_kick(i);
  return o;
}

bool same_bytes(const std::vector<vec4>& a, const std::vector<vec4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(vec4)) == 0;
}

}  // namespace

TEST_CASE("kick_drift and gather_kick in SIMD lanes: the scalar kernels' bytes on every SIMD target", "[engine][bitexact]") {
  KickScene s(7);
  int moved_fixed = 0;
  for (int64_t target : contact_lanes_targets()) {
    pin_contact_lanes_target(target);
    for (Pass pass : {Pass::KickDrift, Pass::GatherKick})
      for (uint flags : {0u, kFlagDrift})
        for (float kick : {0.0f, 0.5f, 1.0f})
          for (float air_drag : {0.0f, 0.3f})
            for (float skin_sq : {1e6f, 1e-9f}) {  // no particle past half the skin, or some
              KickOutputs scalar = run_pass(s, pass, flags, kick, air_drag, skin_sq, false);
              KickOutputs lanes = run_pass(s, pass, flags, kick, air_drag, skin_sq, true);
              INFO("pass " << int(pass) << ", flags " << flags << ", kick " << kick << ", air_drag " << air_drag
                           << ", skin^2 " << skin_sq << ", lanes on " << contact_lanes_target());
              CHECK(same_bytes(scalar.pos, lanes.pos));
              CHECK(same_bytes(scalar.vel, lanes.vel));
              CHECK(same_bytes(scalar.omega, lanes.omega));
              CHECK(same_bytes(scalar.force, lanes.force));
              CHECK(same_bytes(scalar.torque, lanes.torque));
              CHECK(scalar.control == lanes.control);
              // The scene must exercise what it says: a kick changes the moving ones' velocities, not
              // the fixed ones'; gather_kick kicks (and drifts) only with a kick.
              CHECK((std::memcmp(&scalar.vel[1], &s.vel[1], sizeof(vec4)) != 0) == (kick > 0.0f));
              moved_fixed += std::memcmp(&scalar.vel[0], &s.vel[0], sizeof(vec4)) != 0;
              moved_fixed += std::memcmp(&scalar.pos[0], &s.pos[0], sizeof(vec4)) != 0;
              bool runs_kick = pass == Pass::KickDrift || kick > 0.0f;
              CHECK(scalar.control[kCtlNeedRebuild] == (runs_kick && (flags & kFlagDrift) && skin_sq < 1.0f ? 1u : 0u));
            }
  }
  pin_contact_lanes_target(0);
  CHECK(moved_fixed == 0);
}
