// A sphere in double precision: the building block of clumps, heaps and sphere CSV files.
#pragma once
#include <glm/vec3.hpp>

namespace repose {

struct Sphere {
  glm::dvec3 centre{0.0};  // metres
  double radius = 0.0;     // metres, > 0
};

}  // namespace repose
