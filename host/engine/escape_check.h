// Particles that left the domain: passed through a wall (behind a plane or box face, outside a
// cylinder within its height, by more than their diameter) or flew far beyond everything the case
// holds. A run warns about the first one instead of carrying it on silently (a particle at 1e6
// m/s otherwise ends 40 km below the floor without a word).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/backend.h"
#include "engine/model.h"

namespace repose {

struct Escape {
  uint32_t particle = 0;
  std::string where;  // "0.12 m behind the wall 'floor'", "3.2 km from the domain"
};

class EscapeCheck {
 public:
  explicit EscapeCheck(const Model& model);
  // The first escaped particle of `pos` at time t (walls where they are then), if any: its index
  // in `pos`, which is its global id when pos is by global id.
  std::optional<Escape> find(const std::vector<gpu::vec4>& pos, double t) const;

 private:
  const Model& model_;
  Vec3d centre_{};
  double reach_ = 0;  // farther than this from centre_ is out of the domain
};

}  // namespace repose
