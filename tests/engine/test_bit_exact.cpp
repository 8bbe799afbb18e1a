// The CPU twin and lavapipe must agree to the byte, for every thread count and kernel variant.
#include <catch2/catch.hpp>
#include <random>

#include "case/case_loader.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

TEST_CASE("settling box of 2400 spheres: lavapipe and CPU twin identical after 1000 steps",
          "[engine][bitexact]") {
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml");
  REQUIRE(spec.spheres.size() >= 2000);
  auto cpu1 = simulate(spec, "cpu", 1);
  auto cpu2 = simulate(spec, "cpu", 2);
  auto gpu = simulate(spec, "vulkan");
  cpu1->advance(1000);
  cpu2->advance(1000);
  gpu->advance(1000);
  // The run must exercise what it claims: wall and particle contacts with history, rebuilds.
  const HostState& s = cpu1->state();
  size_t wall_contacts = 0, particle_contacts = 0, with_history = 0;
  for (size_t c = 0; c < s.partner.size(); ++c) {
    (s.partner[c] >= spec.spheres.size() ? wall_contacts : particle_contacts)++;
    if (s.history[c].x != 0 || s.history[c].y != 0 || s.history[c].z != 0) ++with_history;
  }
  CHECK(wall_contacts > 50);
  CHECK(particle_contacts > 500);
  CHECK(with_history > 100);
  CHECK(cpu1->rebuilds() > 5);
  std::string which_threads, which_backend;
  bool same_threads = same_state(cpu1->state(), cpu2->state(), &which_threads);
  bool same_backend = same_state(cpu1->state(), gpu->state(), &which_backend);
  INFO("1 vs 2 threads differ in: " << which_threads << "; cpu vs vulkan differ in: " << which_backend);
  CHECK(same_threads);
  CHECK(same_backend);
}

TEST_CASE("kernel variants give the same bytes as each other and as the CPU twin",
          "[engine][bitexact]") {
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml");
  auto reference = simulate(spec, "cpu", 2);
  reference->advance(150);
  for (const char* text : {"rows,wg=64", "contact,wg=32", "contact,wg=256", "rows,wg=128",
                           "contact,lean,wg=64", "rows,lean,wg=32", "contact,lean,wg=128"}) {
    KernelVariant v = KernelVariant::parse(text);
    for (const char* backend : {"cpu", "vulkan"}) {
      auto sim = simulate(spec, backend, 2, v);
      sim->advance(150);
      std::string which;
      bool same = same_state(reference->state(), sim->state(), &which);
      INFO(backend << " " << text << " differs in " << which);
      CHECK(same);
    }
  }
}

// Random clouds whose sizes straddle workgroup boundaries (n = WG-1, WG, WG+1) with walls,
// so partially filled workgroups and every kernel's bounds checks are exercised.
TEST_CASE("random clouds around workgroup boundaries: twin and lavapipe identical",
          "[engine][bitexact]") {
  for (uint32_t wg : {32u, 64u}) {
    for (uint32_t n : {1u, wg - 1, wg, wg + 1, 2 * wg + 1}) {
      // Loose cloud on a coarse jittered grid, moving at random.
      CaseSpec cloud = seeded_cloud(n, n * 1000 + wg, 2.5, 0.3);
      KernelVariant v;
      v.workgroup = wg;
      auto cpu = simulate(cloud, "cpu", 2, v, 7);
      auto gpu = simulate(cloud, "vulkan", 1, v, 7);
      cpu->advance(60);
      gpu->advance(60);
      std::string which;
      bool same = same_state(cpu->state(), gpu->state(), &which);
      INFO("n = " << n << ", wg = " << wg << ", first differing array: " << which);
      CHECK(same);
    }
  }
}

// The lean contact entry rebuilds torques in the gather; with LIGGGHTS's relative rolling torque
// it reads both spins (and kicks in a pass of its own), with symplectic Euler it drifts there.
TEST_CASE("lean entries equal full entries: relative rolling omega, symplectic Euler, spring cap",
          "[engine][bitexact]") {
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml");
  spec.contact.rolling_omega = RollingOmega::Relative;
  spec.contact.coulomb_cap = CoulombCap::SpringOnly;
  for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::SymplecticEuler}) {
    spec.integrator = integrator;
    auto reference = simulate(spec, "cpu", 2);
    reference->advance(150);
    for (const char* text : {"contact,lean", "rows,lean,wg=32"}) {
      for (const char* backend : {"cpu", "vulkan"}) {
        auto sim = simulate(spec, backend, 2, KernelVariant::parse(text));
        sim->advance(150);
        std::string which;
        bool same = same_state(reference->state(), sim->state(), &which);
        INFO(backend << " " << text << (integrator == Integrator::SymplecticEuler ? " SE" : " VV")
                     << " differs in " << which);
        CHECK(same);
      }
    }
  }
}

// Rows of the contact list are sorted by partner and separated entries add exact zeros, so the
// list's extra (not touching) entries and the moments it is rebuilt change nothing: the skin and
// the rebuild policy are free choices for speed. Particles, forces and wall forces must be
// identical to the byte for a skin 1/5 and 3 times the default, and for a rebuild every step.
TEST_CASE("the neighbour skin and the rebuild interval leave every particle byte unchanged",
          "[engine][bitexact]") {
  CaseSpec spec = load_case(std::string(REPOSE_SOURCE_DIR) + "/cases/settle_box.toml");
  double skin = build_model(spec).skin;
  auto run = [&](double s, int interval, const char* variant) {
    return simulate_with_list(spec, s, interval, 400, KernelVariant::parse(variant));
  };
  auto reference = run(skin, 0, "contact");
  REQUIRE(reference->rebuilds() > 5);
  auto ref_walls = reference->wall_forces();
  for (const char* variant : {"contact", "rows,lean"}) {
    for (auto [s, interval] : {std::pair{0.2 * skin, 0}, std::pair{3.0 * skin, 0}, std::pair{skin, 1}}) {
      auto other = run(s, interval, variant);
      CHECK(other->rebuilds() != reference->rebuilds());
      const HostState &a = reference->state(), &b = other->state();
      INFO(variant << ", skin " << s << " m, rebuild interval " << interval);
      CHECK(same_bytes(a.pos, b.pos));
      CHECK(same_bytes(a.vel, b.vel));
      CHECK(same_bytes(a.omega, b.omega));
      CHECK(same_bytes(a.force, b.force));
      CHECK(same_bytes(a.torque, b.torque));
      auto walls = other->wall_forces();
      REQUIRE(walls.size() == ref_walls.size());
      for (size_t w = 0; w < walls.size(); ++w)
        CHECK((walls[w].fx == ref_walls[w].fx && walls[w].fy == ref_walls[w].fy && walls[w].fz == ref_walls[w].fz));
    }
  }
}
