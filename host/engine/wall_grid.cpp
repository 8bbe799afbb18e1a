#include "engine/wall_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <utility>

#include "geometry/closest_point.h"
#include "twin_kernels.h"

namespace repose {

namespace {

// The kernels clamp a cell number to +-2^20 (cell_coord); the grid stays inside that.
constexpr double kCellLimit = 1048576.0 - 4.0;
constexpr double kFloatEpsilon = 5.96e-8;  // 2^-24, a float's relative rounding
// A triangle near more cells than this (a floor or plate of a few triangles, ~1 m^2 at 15 mm
// cells) is tested by every sphere instead: it costs one test each, where its cells would cost
// memory and setup time growing with its area.
constexpr size_t kMostCellsPerTriangle = 4096;
// Times a cell is halved when its centre alone cannot tell (box_near): the cells a triangle is
// entered in lie within its reach plus an eighth of a cell's diagonal.
constexpr int kBoxRefinements = 2;

glm::dvec3 corner(const gpu::vec4& v) { return {double(v.x), double(v.y), double(v.z)}; }
glm::dvec3 corner(const Vec3d& v) { return {v[0], v[1], v[2]}; }

// The largest radius of a sphere that walks the grid, as the kernels hold it (above
// Model::large_radius a sphere tests every wall: walk_walls).
double grid_radius(const Model& m) {
  float large = float(m.large_radius);
  float r = 0.0f;
  for (const gpu::vec4& p : m.pos)
    if (!(p.w > large)) r = std::max(r, p.w);
  return double(r);
}

// The cell edge the kernels number cells by: they multiply a coordinate by float(1 / cell).
double kernel_cell(const Model& m) { return 1.0 / double(float(1.0 / m.cell)); }

// The float face test of closest_on_triangle can take a point just beyond an edge of a long thin
// triangle for its face (then only the plane's distance is tested): its cross terms round by
// about eps L^2 |p - a| against the twice area, so up to about eps L^3 / (2 area) beyond it
// (measured: at most 0.92 of that over 8e7 points around the slivers of hoppers of 16 to
// 100,000 sides, 0.26 mm at 100,000). Four times that.
double sliver_slack(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  double longest = std::max(glm::length(b - a), std::max(glm::length(c - b), glm::length(a - c)));
  return 4.0 * kFloatEpsilon * longest * longest * longest / glm::length(glm::cross(b - a, c - a));
}

// wall_contact accepts a sphere by exact arithmetic within radius + skin (`touching`) of the
// triangle, plus the float roundings: of the coordinates (1e-4 of their size, as
// part_may_meet_wall allows) and of the face test (sliver_slack).
double triangle_reach(double touching, const gpu::WallState& t) {
  glm::dvec3 a = corner(t.p0), b = corner(t.p1), c = corner(t.p2);
  glm::dvec3 extent = glm::max(glm::abs(a), glm::max(glm::abs(b), glm::abs(c)));
  double size = std::max(extent.x, std::max(extent.y, extent.z));
  return touching + 1e-4 * (size + touching) + sliver_slack(a, b, c);
}

struct Triangle {
  glm::dvec3 a, b, c;
  double distance(glm::dvec3 p) const { return glm::length(p - closest_point_on_triangle(p, a, b, c).point); }
};

// False only when no point of the cube about `centre` (half its edge `half`) is within `reach`
// of t: its centre farther than reach plus half its diagonal, or, where that cannot tell, each of
// its eighths so, `depth` times over.
bool box_near(const Triangle& t, glm::dvec3 centre, double half, double reach, int depth) {
  double d = t.distance(centre);
  if (d < reach) return true;
  if (d >= reach + std::sqrt(3.0) * half) return false;
  if (depth == 0) return true;
  for (int k = 0; k < 8; ++k) {
    glm::dvec3 eighth(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
    if (box_near(t, centre + eighth * half, 0.5 * half, reach, depth - 1)) return true;
  }
  return false;
}

using CellWall = std::pair<uint64_t, uint32_t>;  // a cell (three 21-bit numbers) and a wall

constexpr int64_t kKeyOffset = int64_t(1) << 20;
uint64_t cell_key(glm::dvec3 cell) {
  return uint64_t(int64_t(cell.z) + kKeyOffset) << 42 | uint64_t(int64_t(cell.y) + kKeyOffset) << 21 |
         uint64_t(int64_t(cell.x) + kKeyOffset);
}
int key_axis(uint64_t key, int shift) { return int(int64_t((key >> shift) & 0x1fffff) - kKeyOffset); }

// Appends (cell, w) for each cell of edge h from which a sphere centre may come within `reach`
// of triangle s (box_near: a centre in the cell as the kernels' float floor assigns it is in the
// cell but for a rounding inside the reach's slack). The cells of the bounding box are visited in
// rows along the axis the normal is most nearly along, a row only when its line comes that near
// the triangle and only where its cells may lie that near the triangle's plane. False, and
// nothing appended, when the cells lie beyond those the kernels number or are more than
// kMostCellsPerTriangle.
bool triangle_cells(const gpu::WallState& s, double reach, double h, uint32_t w, std::vector<CellWall>& out) {
  Triangle t{corner(s.p0), corner(s.p1), corner(s.p2)};
  glm::dvec3 lo = glm::floor((glm::min(t.a, glm::min(t.b, t.c)) - reach) / h) - 1.0;
  glm::dvec3 hi = glm::floor((glm::max(t.a, glm::max(t.b, t.c)) + reach) / h) + 1.0;
  for (int k = 0; k < 3; ++k)
    if (!(lo[k] > -kCellLimit && hi[k] < kCellLimit)) return false;
  double within = reach + 0.5 * std::sqrt(3.0) * h;
  glm::dvec3 n = glm::normalize(glm::cross(t.b - t.a, t.c - t.a));
  glm::dvec3 an = glm::abs(n);
  int k = an.x >= an.y && an.x >= an.z ? 0 : an.y >= an.z ? 1 : 2;  // the rows' axis: |n_k| >= 1/sqrt(3)
  int i = (k + 1) % 3, j = (k + 2) % 3;
  Triangle flat = t;  // seen along the rows: a row's cells can meet t only where its line meets this
  flat.a[k] = flat.b[k] = flat.c[k] = 0.0;
  size_t before = out.size();
  glm::dvec3 cell(0.0);
  for (cell[i] = lo[i]; cell[i] <= hi[i]; ++cell[i])
    for (cell[j] = lo[j]; cell[j] <= hi[j]; ++cell[j]) {
      glm::dvec3 axis(0.0);
      axis[i] = (cell[i] + 0.5) * h;
      axis[j] = (cell[j] + 0.5) * h;
      if (flat.distance(axis) >= within) continue;
      // Cell centres with n . (centre - a) within +-`within`, solved for coordinate k.
      double rest = n[i] * (axis[i] - t.a[i]) + n[j] * (axis[j] - t.a[j]);
      double k0 = t.a[k] + (-rest - within) / n[k], k1 = t.a[k] + (-rest + within) / n[k];
      double first = std::max(lo[k], std::floor(std::min(k0, k1) / h - 0.5) - 1.0);
      double last = std::min(hi[k], std::floor(std::max(k0, k1) / h - 0.5) + 1.0);
      for (cell[k] = first; cell[k] <= last; ++cell[k])
        if (box_near(t, (cell + 0.5) * h, 0.5 * h, reach, kBoxRefinements)) out.push_back({cell_key(cell), w});
      if (out.size() - before > kMostCellsPerTriangle) {
        out.resize(before);
        return false;
      }
    }
  return true;
}

// The grid's words (walk_walls) for `cells`, sorted by cell and wall, in a table of the kernels'
// hash (cell_hash) with about two buckets per cell: each bucket's cells in key order, each as
// (x, y, z, count, its walls ascending); then the walls every sphere tests.
WallGrid bucketed(const std::vector<CellWall>& cells, const std::vector<uint32_t>& always) {
  std::vector<std::pair<size_t, size_t>> runs;  // each cell's [begin, end) in `cells`
  for (size_t k = 0; k < cells.size(); ++k)
    if (k == 0 || cells[k].first != cells[k - 1].first) runs.push_back({k, k + 1});
    else runs.back().second = k + 1;
  WallGrid g;
  uint32_t t = g.table_size = std::bit_ceil(uint32_t(std::max<size_t>(1024, 2 * runs.size())));
  gpu::Kernels kernels;
  std::vector<uint32_t> bucket(runs.size()), start(t + 1, 0u);
  for (size_t r = 0; r < runs.size(); ++r) {
    uint64_t key = cells[runs[r].first].first;
    bucket[r] = kernels.cell_hash(key_axis(key, 0), key_axis(key, 21), key_axis(key, 42), t);
    ++start[bucket[r] + 1];
  }
  for (uint32_t b = 0; b < t; ++b) start[b + 1] += start[b];
  std::vector<size_t> order(runs.size());  // the cells by bucket, in key order within one
  for (size_t r = 0; r < runs.size(); ++r) order[start[bucket[r]]++] = r;
  g.words.assign(t + 2, 0u);
  g.words.reserve(t + 2 + 4 * runs.size() + cells.size() + always.size());
  for (size_t o = 0, b = 0; o <= order.size(); ++o) {
    uint32_t here = o < order.size() ? bucket[order[o]] : t;
    while (b <= here && b < t) g.words[b++] = uint32_t(g.words.size());  // this and any empty buckets before
    if (o == order.size()) break;
    auto [begin, end] = runs[order[o]];
    uint64_t key = cells[begin].first;
    for (int shift : {0, 21, 42}) g.words.push_back(uint32_t(key_axis(key, shift)));
    g.words.push_back(uint32_t(end - begin));
    for (size_t e = begin; e < end; ++e) g.words.push_back(cells[e].second);
  }
  g.words[t] = uint32_t(g.words.size());
  g.words.insert(g.words.end(), always.begin(), always.end());
  g.words[t + 1] = uint32_t(g.words.size());
  return g;
}

}  // namespace

bool wall_in_grid(const Model& m, size_t w) {
  const ModelWall& mw = m.walls[w];
  if (mw.kind != gpu::kWallTriangle || has_motion(mw.motion)) return false;
  glm::dvec3 a = corner(mw.p0), b = corner(mw.p1), c = corner(mw.p2);
  return sliver_slack(a, b, c) < glm::length(b - a) + glm::length(c - b);  // else too thin to trust: tested always
}

bool wall_grid_pays(const Model& m) {
  size_t n = 0;
  for (size_t w = 0; w < m.walls.size(); ++w) n += wall_in_grid(m, w);
  return n >= kWallGridMinTriangles;
}

double wall_grid_reach(const Model& m, const gpu::WallState& t) {
  return triangle_reach(grid_radius(m) + double(float(m.skin)), t);
}

WallGrid build_wall_grid(const Model& m) {
  double h = kernel_cell(m), touching = grid_radius(m) + double(float(m.skin));
  std::vector<CellWall> cells;
  std::vector<uint32_t> always;
  for (size_t w = 0; w < m.walls.size(); ++w) {
    if (!wall_in_grid(m, w)) {
      always.push_back(uint32_t(w));
      continue;
    }
    gpu::WallState s = m.wall_state(w, 0.0);  // a still wall's row at every step
    if (!triangle_cells(s, triangle_reach(touching, s), h, uint32_t(w), cells)) always.push_back(uint32_t(w));
  }
  if (cells.empty()) return {};
  std::sort(cells.begin(), cells.end());
  return bucketed(cells, always);
}

std::string describe_wall_grid(const Model& m) {
  std::string rows = std::to_string(m.walls.size()) + " wall rows";
  uint32_t t = m.wall_table_size;
  if (m.wall_grid.empty()) return rows + ", no wall grid: every sphere tests every wall";
  size_t always = m.wall_grid[t + 1] - m.wall_grid[t], cells = 0, entries = 0;
  for (uint32_t s = t + 2; s < m.wall_grid[t]; s += 4 + m.wall_grid[s + 3]) {
    ++cells;
    entries += m.wall_grid[s + 3];
  }
  char text[256];
  std::snprintf(text, sizeof text,
                ": %zu in the wall grid (%zu cells, %.1f triangles per cell, %u buckets), %zu tested by every sphere",
                m.walls.size() - always, cells, double(entries) / double(std::max<size_t>(1, cells)), t, always);
  return rows + text;
}

void set_wall_grid(Model& m) {
  WallGrid g = build_wall_grid(m);
  m.wall_grid = std::move(g.words);
  m.wall_table_size = g.table_size;
}

}  // namespace repose
