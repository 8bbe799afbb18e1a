// The contact kernel in SIMD lanes (kernels_ref/contact_lanes.cpp) against the scalar kernel it
// mirrors, for every combination of the options the lanes take: same bytes in every output.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <string_view>
#include <vector>

#include "contact_lanes.h"
#include "twin_kernels.h"

using namespace repose::gpu;

namespace {

// Random particles, bodies, material pairs and contacts: touching and not, coincident centres,
// zero and non-zero spins and histories, pairs with each extension off and on, two plane walls
// (the floor z = 5 mm; a tilted lid sliding and turning, of another material), a cylinder and a
// rectangle (a plate facing down, touched on its face and at its edges) as the partners of some
// contacts, in runs of lanes and alone, all four kinds in one batch (the lanes measure planes,
// cylinders and a rectangle's face in the batch's lanes, and a rectangle's edges one by one, the
// law of a batch of those together, and of the last few at the end), runs of lanes whose pairs are all apart (the
// lanes then store zeros without the law), runs whose owners are a few consecutive slots, and a
// touching run whose owners and partners each belong to one body (their rows then load once).
struct Scene {
  std::vector<vec4> pos, vel, omega, history;
  std::vector<uint> material, partner, owner;
  std::vector<PairParams> pairs;
  std::vector<SubSphere> subs;
  std::vector<Body> bodies;
  std::vector<WallState> walls;
  uint n_materials;
  int32_t uniform_material = -1;  // Buffers::uniform_material: every particle's, when they share one

  Scene(uint n_particles, uint n_contacts, uint materials, uint64_t seed) : n_materials(materials) {
    std::mt19937 rng{uint32_t(seed)};
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto pick = [&](uint n) { return uint(rng() % n); };
    auto some = [&](float scale) { return u(rng) < 0.3f ? 0.0f : scale * (u(rng) - 0.5f); };
    for (uint i = 0; i < n_particles; ++i) {
      float r = 0.002f + 0.008f * u(rng);
      pos.push_back(vec4(0.03f * u(rng), 0.03f * u(rng), 0.03f * u(rng), r));
      vel.push_back(vec4(some(2.0f), some(2.0f), some(2.0f), 1.0f / (0.001f + 0.1f * u(rng))));
      omega.push_back(vec4(some(50.0f), some(50.0f), some(50.0f), 1.0f / (1e-7f + 1e-5f * u(rng))));
      material.push_back(pick(materials));
      subs.push_back(SubSphere{vec4(0.0f), uvec4(i / 3u, 0u, 0u, 0u)});
    }
    pos[1] = pos[0];  // coincident centres: dist 0, no contact
    pos[3] = pos[2] + vec4(1.0f, 0.0f, 0.0f, 0.0f);  // 2 and 3 a metre apart: whole batches of pairs apart
    for (uint b = 0; b * 3u < n_particles; ++b) {
      Body body{};
      body.pos = vec4(0.03f * u(rng), 0.03f * u(rng), 0.03f * u(rng), 1.0f);
      body.spheres = uvec4(b * 3u, b % 2u ? 1u : 3u, 0u, 0u);  // lone spheres keep their own lever
      bodies.push_back(body);
    }
    for (uint m = 0; m < materials * materials; ++m) {
      // Every row of the pair table, by its unit, so that a new row is drawn with no edit here: a
      // modulus, else a number that is 0 (off) in half the pairs.
      PairParams p{};
      auto draw = [&](std::string_view unit) {
        if (unit == "Pa") return 1e6f + 1e8f * u(rng);
        float scale = unit == "s" ? 1e-5f : unit == "J/m^3" ? 1e4f : 0.8f;
        return u(rng) < 0.5f ? 0.0f : scale * u(rng);
      };
#define REPOSE_DRAW_PARAM(name, unit, source) p.name = draw(#unit);
      REPOSE_PAIR_PARAMS(REPOSE_DRAW_PARAM)
#undef REPOSE_DRAW_PARAM
      pairs.push_back(p);
    }
    WallState floor{};
    floor.info = uvec4(kWallPlane, 0u, 0u, 0u);
    floor.p0 = vec4(0.0f, 0.0f, 0.005f, 0.0f);
    floor.p1 = vec4(0.0f, 0.0f, 1.0f, 0.0f);
    walls.push_back(floor);
    WallState lid{};  // tilted, sliding and turning, of another material: its contacts' v_rel and pairs
    lid.info = uvec4(kWallPlane, 1u % materials, 0u, 0u);
    lid.p0 = vec4(0.015f, 0.015f, 0.02f, 0.0f);
    lid.p1 = vec4(0.6f, 0.0f, -0.8f, 0.0f);
    lid.vel = vec4(0.1f, -0.2f, 0.05f, 0.0f);
    lid.omega = vec4(1.0f, 2.0f, -3.0f, 0.0f);
    lid.centre = vec4(0.01f, 0.01f, 0.01f, 0.0f);
    walls.push_back(lid);
    WallState drum{};  // a cylinder about the vertical through the scene's middle
    drum.info = uvec4(kWallCylinder, 0u, 0u, 0u);
    drum.p0 = vec4(0.015f, 0.015f, 0.0f, 0.0f);
    drum.p1 = vec4(0.0f, 0.0f, 1.0f, 0.012f);
    drum.vel = vec4(0.0f, 0.0f, 0.0f, 0.02f);  // its top below some centres: beyond its end
    walls.push_back(drum);
    WallState plate{};  // a square plate facing down over the middle: face lanes and edge lanes
    plate.info = uvec4(kWallRectangle, 0u, 0u, 0u);
    plate.p0 = vec4(0.015f, 0.015f, 0.025f, 0.0f);
    plate.p1 = vec4(0.0f, 0.0f, -1.0f, 0.0f);
    plate.p2 = vec4(1.0f, 0.0f, 0.0f, 0.008f);
    plate.p3 = vec4(0.0f, 1.0f, 0.0f, 0.008f);
    walls.push_back(plate);
    for (uint c = 0; c < n_contacts; ++c) {
      uint i = pick(n_particles), j = pick(n_particles);
      if (j == i) j = (i + 1u) % n_particles;
      if (c % 97u == 0u) i = 0u, j = 1u;
      // Owners in rows, as a list holds them (the lanes then load the batch's owner rows as one
      // block): four entries each, then sixteen owners spanning 15 slots (a block), then 16 (not).
      if (c >= 480u && c < 560u) i = 40u + (c - 480u) / 4u;
      if (c >= 560u && c < 576u) i = 60u + (c - 560u);
      if (c >= 576u && c < 592u) i = 80u + (c - 576u) + (c == 591u ? 1u : 0u);
      if (j == i) j = (i + 1u) % n_particles;
      if (c == 591u) j = 97u;  // touching (below): a wrong owner row would show
      if (c % 23u == 0u || (c >= 200u && c < 216u)) j = n_particles;  // the floor
      if (c % 31u == 0u || (c >= 400u && c < 420u)) j = n_particles + 1u;  // the lid
      if (c % 37u == 0u || (c >= 212u && c < 216u)) j = n_particles + 2u;  // the drum, beside the floor
      if ((c % 11u == 5u && j < n_particles) || (c >= 216u && c < 220u)) j = n_particles + 3u;  // the plate, beside both
      if (c >= 304u && c < 336u) i = 2u, j = 3u;
      if (c >= 600u && c < 632u) i = 96u, j = 97u;  // touching, one body each side for the whole batch,
      if (c == 631u) i = 99u;  // then for all but the last lane's owner
      owner.push_back(i);
      partner.push_back(j);
      history.push_back(vec4(some(1e-4f), some(1e-4f), some(1e-4f), float(pick(100))));
    }
    pos[97] = pos[96] + vec4(0.002f, 0.0f, 0.0f, 0.0f);  // radii of 2 mm or more: they overlap
    pos[99] = pos[96] + vec4(0.0f, 0.002f, 0.0f, 0.0f);  // and 99 overlaps 97 (2.8 mm apart)
  }
};

// The contact kernel's outputs over the scene, in lanes or by the scalar kernel.
struct Outputs {
  std::vector<vec4> history, force, torque_i, torque_j;
};

// The scene's buffers and o's as the kernels see them.
Kernels bind(const Scene& s, Outputs& o, uint flags) {
  Kernels k;
  k.B_pos = const_cast<vec4*>(s.pos.data());
  k.B_vel = const_cast<vec4*>(s.vel.data());
  k.B_omega = const_cast<vec4*>(s.omega.data());
  k.B_material = const_cast<uint*>(s.material.data());
  k.B_pairs = const_cast<PairParams*>(s.pairs.data());
  k.B_partner = const_cast<uint*>(s.partner.data());
  k.B_owner = const_cast<uint*>(s.owner.data());
  k.B_subs = const_cast<SubSphere*>(s.subs.data());
  k.B_bodies = const_cast<Body*>(s.bodies.data());
  k.B_walls = const_cast<WallState*>(s.walls.data());
  k.PC.n_walls = uint(s.walls.size());
  k.B_history = o.history.data();
  k.B_contact_force = o.force.data();
  k.B_torque_i = o.torque_i.data();
  k.B_torque_j = o.torque_j.data();
  k.PC.n_particles = uint(s.pos.size());
  k.PC.n_materials = s.n_materials;
  k.PC.flags = flags;
  k.PC.dt = 1e-5f;
  k.uniform_material = s.uniform_material;
  return k;
}

Outputs run(const Scene& s, uint flags, bool lanes) {
  Outputs o;
  size_t n = s.owner.size();
  o.history = s.history;
  o.force.assign(n, vec4(7.0f));
  o.torque_i.assign(n, vec4(7.0f));
  o.torque_j.assign(n, vec4(7.0f));
  Kernels k = bind(s, o, flags);
  if (lanes)
    contact_forces_lanes(k, 0, n);
  else
    for (uint c = 0; c < n; ++c) k.process_contact(s.owner[c], c);
  return o;
}

bool same_bytes(const std::vector<vec4>& a, const std::vector<vec4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(vec4)) == 0;
}

}  // namespace

TEST_CASE("contact kernel in SIMD lanes: the scalar kernel's bytes for every option it covers, on every SIMD target", "[engine][bitexact]") {
  // Every subset of the options the lanes take, on every SIMD target this machine has (SSE4,
  // AVX2, AVX-512 here); 16 * 40 + 9 contacts so that a tail runs scalar.
  const uint options[] = {kFlagCoulombSpringOnly, kFlagClipAttraction,        kFlagRollingConstTorque,
                          kFlagRollingRelativeOmega, kFlagKeepHistory,        kFlagLeanContacts,
                          kFlagBodies,            kFlagCohesionContactFriction, kFlagRollingLeverSphere,
                          kFlagCohesionIntersection};
  const uint n_options = sizeof(options) / sizeof(options[0]);
  Scene many(120, 16 * 40 + 9, 3, 11), one(120, 16 * 40 + 9, 1, 12), same(120, 16 * 40 + 9, 3, 14);
  same.material.assign(same.material.size(), 2u);  // three materials, the walls' differ, the particles' all 2
  same.uniform_material = 2;
  for (int64_t target : contact_lanes_targets()) {
    pin_contact_lanes_target(target);
    for (const Scene* s : {&many, &one, &same}) {
      for (uint subset = 0; subset < (1u << n_options); ++subset) {
        uint flags = 0;
        for (uint b = 0; b < n_options; ++b)
          if (subset & (1u << b)) flags |= options[b];
        REQUIRE(contact_lanes_cover(flags));
        Outputs scalar = run(*s, flags, false), lanes = run(*s, flags, true);
        INFO("flags " << flags << ", materials " << s->n_materials << " (the particles' all " << s->uniform_material
                       << ", -1: not), lanes on " << contact_lanes_target());
        CHECK(same_bytes(scalar.history, lanes.history));
        CHECK(same_bytes(scalar.force, lanes.force));
        CHECK(same_bytes(scalar.torque_i, lanes.torque_i));
        if ((flags & kFlagLeanContacts) == 0u) CHECK(same_bytes(scalar.torque_j, lanes.torque_j));
      }
    }
  }
  pin_contact_lanes_target(0);
  // The scene must exercise both sides of the kernel: some contacts touch, some do not.
  Outputs o = run(many, kFlagRollingConstTorque, false);
  int touching_contacts = 0;
  for (const vec4& f : o.force) touching_contacts += f.x != 0.0f;
  CHECK(touching_contacts > 100);
  CHECK(touching_contacts < int(o.force.size()) - 100);
  // ... and the wall contacts fill more than one batch of lanes, each wall some of them.
  int on_wall[4] = {0, 0, 0, 0}, plate_face = 0;
  for (size_t c = 0; c < o.force.size(); ++c)
    if (many.partner[c] >= many.pos.size() && o.force[c].x != 0.0f) {
      const size_t w = many.partner[c] - many.pos.size();
      ++on_wall[w];
      const vec4 x = many.pos[many.owner[c]];
      if (w == 3u && std::abs(x.x - 0.015f) <= 0.008f && std::abs(x.y - 0.015f) <= 0.008f) ++plate_face;
    }
  CHECK(on_wall[0] >= 5);
  CHECK(on_wall[1] >= 5);
  CHECK(on_wall[2] >= 5);
  CHECK(plate_face >= 3);                 // touched on its face (in the lanes) ...
  CHECK(on_wall[3] - plate_face >= 3);    // ... and at its edges (one by one)
  CHECK(on_wall[0] + on_wall[1] > 16);
}

TEST_CASE("contact lanes leave rolling springs and spinning friction to the scalar kernel", "[engine]") {
  CHECK_FALSE(contact_lanes_cover(kFlagRollingSpring));
  CHECK_FALSE(contact_lanes_cover(kFlagSpinningFriction | kFlagRollingConstTorque));
}

TEST_CASE("the contact law alone (the bench's compute ceiling) computes what the kernel stores", "[engine][bitexact]") {
  // The ring's batch b holds the lanes of contacts from b * n / kLawRing (particle pairs only: this
  // list has no walls), so the sink of kLawRing batches must hold, field by field, what the
  // kernel stores for those contacts from the same histories. A ceiling that skipped part of the
  // law, or ran it on other rows, would differ.
  Scene s(120, 16 * 40, 2, 13);
  for (size_t c = 0; c < s.partner.size(); ++c)
    if (s.partner[c] >= s.pos.size()) s.partner[c] = (s.owner[c] + 1u) % uint(s.pos.size());
  const size_t L = contact_lanes_width(), n = s.owner.size();
  for (uint flags : {0u, kFlagLeanContacts, kFlagKeepHistory | kFlagRollingConstTorque,
                     kFlagLeanContacts | kFlagCohesionIntersection | kFlagClipAttraction}) {
    Outputs entries = run(s, flags, true);
    std::vector<float> sink(kLawRing * kSinkFloats * L, -1.0f);
    Outputs before;  // the histories as the kernel found them
    before.history = s.history;
    std::vector<uint> control(16, 0u);
    control[kCtlContacts] = uint(n);
    Kernels k = bind(s, before, flags);
    k.B_control = control.data();
    contact_law_lanes(k, kLawRing, sink.data());
    const bool lean = (flags & kFlagLeanContacts) != 0u;
    int differ = 0, touching = 0;
    for (size_t b = 0; b < kLawRing; ++b)
      for (size_t l = 0; l < L; ++l) {
        size_t c = b * n / kLawRing + l;
        const vec4 stored[] = {entries.history[c], entries.force[c], entries.torque_i[c], entries.torque_j[c]};
        for (size_t f = 0; f < (lean ? 12u : kSinkFloats); ++f)  // lean entries have no T_j
          differ += std::memcmp(&stored[f / 4][f % 4], &sink[(b * kSinkFloats + f) * L + l], 4) != 0;
        touching += entries.force[c].x != 0.0f;
      }
    INFO("flags " << flags << ", lanes on " << contact_lanes_target());
    CHECK(differ == 0);
    CHECK(touching > 10);  // the law ran, not only its zeros
  }
}
