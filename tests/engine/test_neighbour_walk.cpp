// The neighbour walk (shaders/kernels/neighbour.h) against every pair tested directly: a row of
// three cells is walked as one run of buckets, or cell by cell where it wraps around the hash
// table's end; small tables make both, and hash collisions, common. The CPU twin's walk in SIMD
// lanes (kernels_ref/walk_lanes.cpp) against the scalar walk: the same candidates in the same order,
// and no load past the walk rows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

#include "contact_lanes.h"
#include "twin_kernels.h"
#include "walk_lanes.h"

using namespace repose::gpu;

namespace {

// Spheres of radius 0.5 at random in a box 10 cells wide (cells of 1.2: a diameter and the
// skin), in slots scrambled against their global ids, a few of them fixed.
// With `large`, every ninth sphere has radius 1.5, beyond the cells' reach: the large bucket.
struct WalkScene {
  uint n = 400;
  float large_radius = 1e9f;
  std::vector<vec4> pos, vel, pos_at_build;
  std::vector<uint> ids;
  std::vector<WallState> walls;
  std::vector<uint> wall_grid;  // B_wall_grid, its table wall_table buckets long (0: every sphere tests every wall)
  uint wall_table = 0;
  explicit WalkScene(uint32_t seed, bool large = false) {
    std::mt19937 rng{seed};
    std::uniform_real_distribution<float> u(-6.0f, 6.0f);
    if (large) large_radius = 0.6f;
    for (uint s = 0; s < n; ++s) {
      pos.push_back(vec4(u(rng), u(rng), u(rng), large && s % 9u == 4u ? 1.5f : 0.5f));
      vel.push_back(vec4(0.0f, 0.0f, 0.0f, s % 7u == 0u ? 0.0f : 1.0f));
    }
    pos_at_build.resize(n);
    ids.resize(2 * n);
    std::iota(ids.begin(), ids.begin() + n, 0u);
    std::shuffle(ids.begin(), ids.begin() + n, rng);
    for (uint s = 0; s < n; ++s) ids[n + ids[s]] = s;
  }
};

// Walls of every kind across the scene: two planes, a cylinder shorter than the scene (centres
// beyond its ends), a plate smaller than the scene (faces, edges and corners), a triangle; then
// planes up to 34 walls, past the 32 the lanes measure. With `grid`, a wall grid of `table`
// empty buckets whose list every sphere tests holds some of them out of order, the triangle and
// a wall past the 32nd among them.
void add_walls(WalkScene& s, bool grid, uint table) {
  auto wall = [](uint type, vec4 p0, vec4 p1, vec4 p2 = vec4(0.0f), vec4 p3 = vec4(0.0f), float height = 0.0f) {
    WallState w{};
    w.p0 = p0;
    w.p1 = p1;
    w.p2 = p2;
    w.p3 = p3;
    w.vel = vec4(0.0f, 0.0f, 0.0f, height);
    w.info = uvec4(type, 0u, 0u, 0u);
    return w;
  };
  const float k = 0.70710677f;  // 1 / sqrt(2)
  s.walls = {wall(kWallPlane, vec4(0.0f, 0.0f, -5.5f, 0.0f), vec4(0.0f, 0.0f, 1.0f, 0.0f)),
             wall(kWallPlane, vec4(0.3f, 0.0f, 0.0f, 0.0f), vec4(k, k, 0.0f, 0.0f)),
             wall(kWallCylinder, vec4(0.0f, 0.0f, -4.0f, 0.0f), vec4(0.0f, 0.0f, 1.0f, 5.5f), vec4(0.0f), vec4(0.0f), 8.0f),
             wall(kWallRectangle, vec4(0.0f, 0.0f, 2.0f, 0.0f), vec4(0.0f, 0.0f, 1.0f, 0.0f), vec4(1.0f, 0.0f, 0.0f, 3.0f),
                  vec4(0.0f, 1.0f, 0.0f, 3.0f)),
             wall(kWallTriangle, vec4(-5.0f, -5.0f, -1.0f, 0.0f), vec4(5.0f, -5.0f, -1.0f, 0.0f),
                  vec4(0.0f, 5.0f, -1.0f, 0.0f), vec4(0.0f, 0.0f, 1.0f, 0.0f))};
  for (uint w = uint(s.walls.size()); w < 34u; ++w)
    s.walls.push_back(wall(kWallPlane, vec4(0.0f, 0.0f, -6.0f + 0.35f * float(w), 0.0f), vec4(0.0f, 0.0f, 1.0f, 0.0f)));
  s.wall_grid.clear();
  s.wall_table = grid ? table : 0u;
  if (!grid) return;
  const std::vector<uint> listed = {3u, 0u, 33u, 4u, 2u, 1u};
  s.wall_grid.assign(table + 1u, table + 2u);  // every bucket empty, and [T]: the list's start
  s.wall_grid.push_back(table + 2u + uint(listed.size()));  // [T + 1]: its end
  s.wall_grid.insert(s.wall_grid.end(), listed.begin(), listed.end());
}

// `count` floats that end where an inaccessible page begins, so that a lane loading past the
// walk rows' padding crashes the test (on the heap such a load reads a neighbour's bytes unseen).
struct GuardedFloats {
  void* base = nullptr;
  size_t bytes = 0;
  float* data = nullptr;
  explicit GuardedFloats(size_t count) {
    const size_t page = size_t(sysconf(_SC_PAGESIZE)), need = count * sizeof(float);
    const size_t pages = (need + page - 1) / page;
    bytes = (pages + 1) * page;
    base = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    REQUIRE(base != MAP_FAILED);
    REQUIRE(mprotect(static_cast<char*>(base) + pages * page, page, PROT_NONE) == 0);
    data = reinterpret_cast<float*>(static_cast<char*>(base) + pages * page - need);
  }
  ~GuardedFloats() { munmap(base, bytes); }
};

// Each slot's count of candidates and the first kCandidateSlots of them in the order
// contact_count finds them with a hash table of `table` buckets, by the scalar walk or in lanes.
using Found = std::vector<std::pair<uint, std::vector<uint>>>;
// What contact_fill wrote: each entry's owner, partner, history and rolling spring.
struct Filled {
  std::vector<uint> owner, partner;
  std::vector<vec4> history, spring;
  bool operator==(const Filled&) const = default;
};
void fill_rows(Kernels& k, uint n, bool lanes, Filled& out);
// With `filled`, contact_fill then runs too (by the kernel or in lanes) from made-up old rows.
Found walk_in_order(const WalkScene& s, uint table, bool lanes, Filled* filled = nullptr) {
  std::vector<vec4> pos = s.pos, vel = s.vel, at_build = s.pos_at_build;
  std::vector<uint> ids = s.ids, cell_of(s.n), cell_start(table + 2, 0u), cell_fill(table + 1, 0u), sorted(s.n);
  std::vector<uint> row_start(s.n + 1), trans_start(s.n + 1), trans_fill(s.n), candidates(s.n * kCandidateSlots);
  std::vector<uint> control(kControlWords, 0u);
  Kernels k;
  k.B_pos = pos.data();
  k.B_vel = vel.data();
  k.B_pos_at_build = at_build.data();
  k.B_ids = ids.data();
  k.B_cell_of = cell_of.data();
  k.B_cell_start = cell_start.data();
  k.B_cell_fill = cell_fill.data();
  k.B_sorted = sorted.data();
  k.B_row_start = row_start.data();
  k.B_trans_start = trans_start.data();
  k.B_trans_fill = trans_fill.data();
  k.B_candidates = candidates.data();
  k.B_control = control.data();
  k.PC.n_particles = s.n;
  k.PC.table_size = table;
  k.PC.inv_cell = 1.0f / 1.2f;
  k.PC.skin = 0.2f;
  k.PC.large_radius = s.large_radius;
  std::vector<WallState> walls = s.walls;
  std::vector<uint> wall_grid = s.wall_grid;
  k.B_walls = walls.data();
  k.B_wall_grid = wall_grid.data();
  k.PC.n_walls = uint(walls.size());
  k.PC.wall_table_size = s.wall_table;
  for (uint i = 0; i < s.n; ++i) k.k_bucket_count(i);
  uint sum = 0;  // the scan of the bucket counts
  for (uint b = 0; b <= table + 1; ++b) std::swap(sum, cell_start[b]), sum += cell_start[b];
  for (uint i = 0; i < s.n; ++i) k.k_bucket_scatter(i);
  for (uint b = 0; b <= table; ++b) k.k_bucket_sort(b);
  GuardedFloats walk_rows(walk_rows_floats(s.n));
  if (lanes) {
    k.walk_rows = walk_rows.data;
    fill_walk_rows(k, 0, s.n);
    contact_count_lanes(k, 0, s.n + 1);
  } else {
    for (uint i = 0; i <= s.n; ++i) k.k_contact_count(i);
  }
  Found found(s.n);
  for (uint i = 0; i < s.n; ++i) {
    auto first = candidates.begin() + i * kCandidateSlots;
    found[i] = {row_start[i], std::vector<uint>(first, first + std::min(row_start[i], kCandidateSlots))};
  }
  if (filled != nullptr) fill_rows(k, s.n, lanes, *filled);
  return found;
}

// The rows scanned, then old rows made up from each sphere's candidates and others, in no order,
// some partners twice (the last one's history is the one kept), some rows longer than a vector;
// the list's capacity a few entries short of the rows, so that the last rows are cut.
void fill_rows(Kernels& k, uint n, bool lanes, Filled& out) {
  uint total = 0;
  for (uint i = 0; i <= n; ++i) std::swap(total, k.B_row_start[i]), total += k.B_row_start[i];
  total = k.B_row_start[n];
  const uint capacity = total > 8u ? total - 5u : total;
  std::mt19937 rng{7u};
  std::vector<uint> old_start(n + 1, 0u), old_partner;
  std::vector<vec4> old_history;
  for (uint i = 0; i < n; ++i) {
    old_start[i] = uint(old_partner.size());
    const uint kept = std::min(k.B_row_start[i + 1u] - k.B_row_start[i], kCandidateSlots);
    const uint length = rng() % 21u;  // up to 20: past kCandidateSlots
    for (uint o = 0; o < length; ++o) {
      const bool theirs = kept > 0u && rng() % 3u != 0u;
      old_partner.push_back(theirs ? k.B_candidates[i * kCandidateSlots + rng() % kept] : uint(rng() % (n + 40u)));
      old_history.push_back(vec4(float(old_partner.size()), float(i), 1.0f, 2.0f));
    }
  }
  old_start[n] = uint(old_partner.size());
  std::vector<vec4> springs(capacity + old_partner.size(), vec4(0.0f));  // the new ones, then the old ones
  for (size_t o = 0; o < old_partner.size(); ++o) springs[capacity + o] = vec4(3.0f, float(o), 0.0f, 1.0f);
  std::vector<uint> control(k.B_control, k.B_control + kControlWords);
  control[kCtlOldContacts] = uint(old_partner.size()) - 3u;  // the old list's last entries not used
  out.owner.assign(total + 16, 0u);
  out.partner.assign(total + 16, 0u);
  out.history.assign(total + 16, vec4(-1.0f));
  out.spring = springs;
  k.B_old_row_start = old_start.data();
  k.B_old_partner = old_partner.data();
  k.B_old_history = old_history.data();
  k.B_owner = out.owner.data();
  k.B_partner = out.partner.data();
  k.B_history = out.history.data();
  k.B_rolling_spring = out.spring.data();
  k.B_control = control.data();
  k.PC.capacity = capacity;
  k.PC.flags |= kFlagRollingSpring;
  if (lanes)
    contact_fill_lanes(k, 0, n + 3u);  // past n: as a workgroup's last invocations
  else
    for (uint i = 0; i < n + 3u; ++i) k.k_contact_fill(i);
}

std::vector<std::set<uint>> walk(const WalkScene& s, uint table) {
  std::vector<std::set<uint>> found;
  for (const auto& [count, row] : walk_in_order(s, table, false)) {
    REQUIRE(count <= kCandidateSlots);
    found.emplace_back(row.begin(), row.end());
    REQUIRE(found.back().size() == row.size());  // nobody twice
  }
  return found;
}

// The same by testing every pair: within the skin, the pair's lower id its owner, two fixed
// spheres never a pair.
std::vector<std::set<uint>> every_pair(const WalkScene& s) {
  std::vector<std::set<uint>> found(s.n);
  for (uint i = 0; i < s.n; ++i)
    for (uint j = 0; j < s.n; ++j) {
      if (s.ids[j] <= s.ids[i] || (s.vel[i].w == 0.0f && s.vel[j].w == 0.0f)) continue;
      float dx = s.pos[i].x - s.pos[j].x, dy = s.pos[i].y - s.pos[j].y, dz = s.pos[i].z - s.pos[j].z;
      float reach = 0.5f + 0.5f + 0.2f;
      if (dx * dx + dy * dy + dz * dz < reach * reach) found[i].insert(j);
    }
  return found;
}

}  // namespace

TEST_CASE("neighbour walk: rows of cells as one run of buckets or cell by cell, every pair found once", "[engine]") {
  for (uint32_t seed : {1u, 2u, 3u}) {
    WalkScene s(seed);
    std::vector<std::set<uint>> expected = every_pair(s);
    size_t pairs = 0;
    for (const auto& row : expected) pairs += row.size();
    REQUIRE(pairs > 100);  // the scene is dense enough to test something
    for (uint table : {4u, 8u, 64u, 1024u}) {  // 4 and 8: most rows wrap, every bucket shared
      INFO("seed " << seed << ", table " << table);
      CHECK(walk(s, table) == expected);
    }
  }
}

TEST_CASE("neighbour walk in SIMD lanes: the scalar walk's candidates in its order, on every SIMD target", "[engine]") {
  for (int64_t target : contact_lanes_targets()) {
    pin_contact_lanes_target(target);
    for (uint32_t seed : {1u, 2u})
      for (bool large : {false, true}) {
        WalkScene s(seed, large);
        for (uint table : {4u, 64u, 1024u}) {
          INFO("target " << target << ", seed " << seed << ", large spheres " << large << ", table " << table);
          CHECK(walk_in_order(s, table, true) == walk_in_order(s, table, false));
        }
      }
  }
  pin_contact_lanes_target(0);
}

TEST_CASE("contact_fill in SIMD lanes: the kernel's rows, histories and springs, on every SIMD target", "[engine]") {
  for (int64_t target : contact_lanes_targets()) {
    pin_contact_lanes_target(target);
    for (uint32_t seed : {1u, 2u, 3u}) {
      WalkScene s(seed, seed == 3u);
      if (seed == 2u) add_walls(s, false, 0u);  // some rows past kCandidateSlots: walked again
      INFO("target " << target << ", seed " << seed);
      Filled lanes, kernel;
      walk_in_order(s, 64u, true, &lanes);
      walk_in_order(s, 64u, false, &kernel);
      CHECK(lanes == kernel);
      size_t carried = 0;  // histories carried from old rows: the test tests something
      for (const vec4& h : kernel.history) carried += h.w == 2.0f ? 1u : 0u;
      CHECK(carried > 100u);
    }
  }
  pin_contact_lanes_target(0);
}

TEST_CASE("neighbour walk in SIMD lanes: walls measured in lanes give the scalar walk's candidates, on every SIMD target",
          "[engine]") {
  for (int64_t target : contact_lanes_targets()) {
    pin_contact_lanes_target(target);
    for (uint32_t seed : {1u, 2u})
      for (bool grid : {false, true}) {
        WalkScene s(seed, seed == 2u);
        add_walls(s, grid, 16u);
        INFO("target " << target << ", seed " << seed << ", wall grid " << grid);
        const Found lanes = walk_in_order(s, 64u, true);
        CHECK(lanes == walk_in_order(s, 64u, false));
        std::vector<uint> by_wall(s.walls.size(), 0u);  // each wall kind found near some spheres
        for (const auto& [count, row] : lanes)
          for (uint j : row)
            if (j >= s.n) by_wall[j - s.n] += 1u;
        for (uint w : {0u, 1u, 2u, 3u, 4u}) CHECK(by_wall[w] > 0u);
        CHECK(by_wall[33] > 0u);
      }
  }
  pin_contact_lanes_target(0);
}
