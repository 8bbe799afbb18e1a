// The wall grid: the still triangles of meshes entered in the buckets of the particle grid's
// cells from which a sphere's centre can come within the skin of touching them, so that a rebuild
// tests each sphere against the few triangles near it instead of every wall
// (shaders/kernels/neighbour.h walk_walls; docs/engineering.md, "The wall grid").
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/model.h"

namespace repose {

// Still triangles from which the grid is used unless the case says otherwise ([neighbour]
// wall_grid): with 2 the walk costs the same either way, with 6 the grid already saves a fifth
// of it (docs/engineering.md, "The wall grid").
inline constexpr size_t kWallGridMinTriangles = 4;

// True when the grid holds wall w: a triangle that never moves. Planes, cylinders and
// rectangles (a rig's few plates, often large) and every moving wall are tested by every sphere.
bool wall_in_grid(const Model& m, size_t w);

// The case's default: a grid when it holds at least kWallGridMinTriangles walls.
bool wall_grid_pays(const Model& m);

// The grid's words (gpu::WallGrid's layout, walk_walls) and its buckets, built from the walls'
// rows as the kernels see them, the grid's cell, the skin and the largest radius that uses the
// grid (the spheres above Model::large_radius test every wall). Empty and 0 when no wall is in
// the grid or the walls lie beyond the cells the kernels can number.
struct WallGrid {
  std::vector<uint32_t> words;
  uint32_t table_size = 0;
};
WallGrid build_wall_grid(const Model& m);

// How far from a still triangle the grid reaches: the largest radius that uses the grid plus the
// skin, and a slack for the kernels' float rounding (engineering.md says how it is sized).
double wall_grid_reach(const Model& m, const gpu::WallState& triangle);

// m.wall_grid and m.wall_table_size from build_wall_grid.
void set_wall_grid(Model& m);

// One line on the walls and the grid, for `repose bench`: "20004 wall rows: 20000 triangles in
// the wall grid (... entries in ... buckets, ... per occupied bucket), 4 tested by every sphere".
std::string describe_wall_grid(const Model& m);

}  // namespace repose
