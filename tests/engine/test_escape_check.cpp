// A particle that passed through a wall or left the domain is found (repose run warns about the
// first one); particles where they belong are not.
#include <catch2/catch.hpp>

#include "engine/escape_check.h"
#include "engine_test_support.h"

using namespace repose;
using namespace repose::test;

TEST_CASE("escape check: behind a plane, outside a cylinder, far from the domain", "[engine]") {
  CaseBuilder b;
  int m = b.material(1000, 5e6, 0.3);
  b.interaction(m, m, 0.5, 0.5, 0.05);
  b.spec.time.rayleigh_fraction = 0.2;
  b.sphere({0, 0, 0.05}, 0.005, m);
  b.sphere({0.02, 0, 0.05}, 0.005, m);
  b.plane({0, 0, 0}, {0, 0, 1}, m);
  WallSpec tube;
  tube.type = WallSpec::Type::Cylinder;
  tube.material = m;
  tube.base = {0, 0, 0};
  tube.axis = {0, 0, 1};
  tube.radius = 0.05;
  tube.height = 0.2;
  tube.name = "tube";
  b.spec.walls.push_back(tube);
  Model model = build_model(b.spec);
  EscapeCheck check(model);
  std::vector<gpu::vec4> pos = model.pos;
  CHECK_FALSE(check.find(pos, 0.0));
  pos[0].z = -0.004;  // touching the floor from below by less than a diameter: still in contact
  CHECK_FALSE(check.find(pos, 0.0));
  pos[1].z = -0.5;  // passed through the floor
  auto behind = check.find(pos, 0.0);
  REQUIRE(behind);
  CHECK(behind->particle == 1);
  CHECK(behind->where.find("behind the wall 'plane0'") != std::string::npos);
  pos[1] = gpu::vec4(0.2f, 0, 0.1f, 0.005f);  // through the tube's side
  behind = check.find(pos, 0.0);
  REQUIRE(behind);
  CHECK(behind->where.find("behind the wall 'tube'") != std::string::npos);
  pos[1] = gpu::vec4(0, 0, -40000.0f, 0.005f);  // tunnelled far below
  behind = check.find(pos, 0.0);
  REQUIRE(behind);
  CHECK(behind->where.find("40 km from the domain") != std::string::npos);
}
