// A contact list that overflows is grown and the evaluation redone: the run must give the bytes
// of one whose list was large enough from the start, both for the velocity Verlet setup
// evaluation in the constructor and for a batch redone inside advance().
#include <catch2/catch.hpp>

#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

namespace {

std::unique_ptr<Simulation> start(const CaseSpec& spec, const std::string& backend, uint32_t first_capacity) {
  return std::make_unique<Simulation>(build_model(spec), make_backend(backend, -1, 1, gpu::kDefaultWorkgroup),
                                      KernelVariant{}, 50, first_capacity);
}

}  // namespace

TEST_CASE("overflow: a grown and redone contact list gives the bytes of an ample one", "[engine][overflow]") {
  for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::SymplecticEuler}) {
    bool verlet = integrator == Integrator::VelocityVerlet;
    CaseSpec spec = wide_skin_pile(integrator);
    uint32_t n = build_model(spec).n_particles;
    for (const char* backend : {"cpu", "vulkan"}) {
      INFO(backend << (verlet ? ", velocity Verlet" : ", symplectic Euler"));
      auto ample = start(spec, backend, 20 * n);
      // 64 entries: velocity Verlet's F(0) overflows in the constructor and grows the list to
      // 1.25 x 1982 + 64; the landing pile overflows that inside advance(), near step 1000.
      auto tiny = start(spec, backend, 64);
      if (verlet) CHECK(tiny->capacity() > 64);
      std::string which;
      bool same_at_start = same_state(ample->state(), tiny->state(), &which);
      INFO("after construction: " << ample->contacts() << " vs " << tiny->contacts() << " contacts, differ in "
                                  << which);
      CHECK(same_at_start);
      ample->advance(1500);
      tiny->advance(1500);
      INFO("capacity " << ample->capacity() << " vs " << tiny->capacity());
      CHECK(ample->retries() == 0);
      CHECK(tiny->retries() > 0);
      which.clear();
      bool same = same_state(ample->state(), tiny->state(), &which);
      INFO("after 1500 steps differ in " << which);
      CHECK(same);
      CHECK(same_bytes(ample->state().control, tiny->state().control));
    }
  }
}
