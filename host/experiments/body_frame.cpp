#include "experiments/body_frame.h"

#include <stdexcept>

namespace repose {

Vec3d body_centre(const HostState& state) {
  double mass = 0;
  Vec3d c{0, 0, 0};
  for (size_t i = 0; i < state.pos.size(); ++i) {
    double m = 1.0 / state.vel[i].w;
    mass += m;
    c[0] += m * state.pos[i].x;
    c[1] += m * state.pos[i].y;
    c[2] += m * state.pos[i].z;
  }
  return {c[0] / mass, c[1] / mass, c[2] / mass};
}

size_t find_wall(const CaseSpec& spec, const std::string& name, const std::string& role) {
  for (size_t w = 0; w < spec.walls.size(); ++w)
    if (name.empty() || spec.walls[w].name == name) return w;
  throw std::runtime_error(spec.path + ": the experiment needs a [[wall]] as the " + role +
                           (name.empty() ? "" : " (named '" + name + "')"));
}

}  // namespace repose
