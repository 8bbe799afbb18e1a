#include "engine/escape_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace repose {

namespace {

std::string metres(double d) {
  char text[32];
  if (d >= 1000) std::snprintf(text, sizeof text, "%.3g km", d / 1000);
  else std::snprintf(text, sizeof text, "%.3g m", d);
  return text;
}

}  // namespace

EscapeCheck::EscapeCheck(const Model& model) : model_(model) {
  // The domain: the particles at the start and every wall point the model holds.
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  auto add = [&](double x, double y, double z) {
    Vec3d p{x, y, z};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  };
  for (const auto& p : model.pos) add(p.x, p.y, p.z);
  for (const auto& w : model.walls) add(w.p0[0], w.p0[1], w.p0[2]);
  double size = 0;
  for (int k = 0; k < 3; ++k) {
    centre_[k] = 0.5 * (lo[k] + hi[k]);
    size = std::max(size, hi[k] - lo[k]);
  }
  // Generous: ten domain sizes, and never under 10 m (a drop rig is a few tens of cm).
  reach_ = std::max(10.0, 10 * size);
}

std::optional<Escape> EscapeCheck::find(const std::vector<gpu::vec4>& pos, double t) const {
  // Planes and cylinders only: a mesh's 20,000 triangles would cost 20,000 tests per particle.
  std::vector<gpu::WallState> walls;
  std::vector<size_t> index;
  for (size_t w = 0; w < model_.walls.size(); ++w) {
    uint32_t kind = model_.walls[w].kind;
    if (kind != gpu::kWallPlane && kind != gpu::kWallCylinder) continue;
    walls.push_back(model_.wall_state(w, t));
    index.push_back(w);
  }
  for (uint32_t i = 0; i < pos.size(); ++i) {
    const auto& p = pos[i];
    double d = std::sqrt((p.x - centre_[0]) * (p.x - centre_[0]) + (p.y - centre_[1]) * (p.y - centre_[1]) +
                         (p.z - centre_[2]) * (p.z - centre_[2]));
    if (!(d <= reach_)) return Escape{i, metres(d) + " from the domain"};
    for (size_t w = 0; w < walls.size(); ++w) {
      const auto& ws = walls[w];
      double behind = 0;
      if (ws.info.x == gpu::kWallPlane) {
        behind = -((p.x - ws.p0.x) * ws.p1.x + (p.y - ws.p0.y) * ws.p1.y + (p.z - ws.p0.z) * ws.p1.z);
      } else if (ws.info.x == gpu::kWallCylinder) {
        double rx = p.x - ws.p0.x, ry = p.y - ws.p0.y, rz = p.z - ws.p0.z;
        double along = rx * ws.p1.x + ry * ws.p1.y + rz * ws.p1.z;
        if (along < 0 || along > ws.vel.w) continue;
        double radial = std::sqrt(std::max(0.0, rx * rx + ry * ry + rz * rz - along * along));
        behind = radial - ws.p1.w;
      }
      if (behind > 2 * p.w) return Escape{i, metres(behind) + " behind the wall '" + model_.walls[index[w]].name + "'"};
    }
  }
  return std::nullopt;
}

}  // namespace repose
