// Deterministic neighbour search and contact list (docs/engineering.md, neighbour search).
// A rebuild happens in a step when a particle moved more than half the skin since the last one
// (or max_interval steps passed); rebuild_args decides on the device and writes the indirect
// dispatch sizes of every rebuild kernel, zero when there is nothing to do, so the host records
// the same command stream every step. Atomics only count integers; every order that reaches a
// float result is fixed by sorting, by global id (repose_shared.h: particles sit in storage slots
// in any order): buckets by id, rows by partner id, transposed rows by owner id; a pair belongs to
// the lower id.
// Sizes spanning 10:1 (a clump's 160 mm core among 5 mm veins) would make cells as big as the
// largest sphere and full of small ones, so particles above PC.large_radius skip the grid: they
// share one extra bucket (index T) that every walk scans. A pair of a small and a large particle
// belongs to the small one's row, a pair of two large ones to the lower id.
#ifndef REPOSE_KERNELS_NEIGHBOUR_H
#define REPOSE_KERNELS_NEIGHBOUR_H

// Indirect arguments for `groups` workgroups, in rows of at most PC.max_groups_x.
void set_groups(uint word, uint groups) {
  B_control[word] = dispatch_columns(groups, PC.max_groups_x);
  B_control[word + 1u] = dispatch_rows(groups, PC.max_groups_x);
  B_control[word + 2u] = 1u;
}

// One invocation: decide whether this step rebuilds the list.
void k_rebuild_args(uint unused) {
  bool due = PC.max_interval > 0u && B_control[kCtlStepsSinceBuild] + 1u >= PC.max_interval;
  bool rebuild = B_control[kCtlNeedRebuild] != 0u || due || B_control[kCtlRebuildCount] == 0u;
  B_control[kCtlNeedRebuild] = 0u;
  B_control[kCtlRebuilding] = rebuild ? 1u : 0u;
  uint wg = PC.workgroup;
  if (rebuild) {
    B_control[kCtlStepsSinceBuild] = 0u;
    B_control[kCtlRebuildCount] = B_control[kCtlRebuildCount] + 1u;
    B_control[kCtlOldContacts] = B_control[kCtlContacts];
    set_groups(kCtlArgsParticles, groups_for(PC.n_particles + 1u, wg));
    set_groups(kCtlArgsBuckets, groups_for(PC.table_size + 2u, wg));
    set_groups(kCtlArgsOne, 1u);
    set_groups(kCtlArgsOldContacts, groups_for(B_control[kCtlContacts], wg));
    set_groups(kCtlArgsParts, groups_for(PC.n_parts, wg));
    set_groups(kCtlArgsBodies, groups_for(PC.n_bodies, wg));
    // The block passes of the scans (shaders/scan.comp): of the T+1 bucket counts, and of the
    // N rows and N transposed rows.
    set_groups(kCtlArgsScanBuckets, scan_blocks_for(PC.table_size + 1u));
    set_groups(kCtlArgsScanParticles, scan_blocks_for(PC.n_particles));
  } else {
    B_control[kCtlStepsSinceBuild] = B_control[kCtlStepsSinceBuild] + 1u;
    set_groups(kCtlArgsParticles, 0u);
    set_groups(kCtlArgsBuckets, 0u);
    set_groups(kCtlArgsOne, 0u);
    set_groups(kCtlArgsOldContacts, 0u);
    set_groups(kCtlArgsNewContacts, 0u);
    set_groups(kCtlArgsParts, 0u);
    set_groups(kCtlArgsBodies, 0u);
    set_groups(kCtlArgsScanBuckets, 0u);
    set_groups(kCtlArgsScanParticles, 0u);
  }
}

// Keep the list being replaced (with its up-to-date histories) to carry histories over.
void k_save_old_rows(uint i) {
  if (i > PC.n_particles) return;
  B_old_row_start[i] = B_row_start[i];
}
void k_save_old_contacts(uint c) {
  if (c >= B_control[kCtlOldContacts]) return;
  B_old_partner[c] = B_partner[c];
  B_old_history[c] = B_history[c];
  if ((PC.flags & kFlagRollingSpring) != 0u) B_rolling_spring[PC.capacity + c] = B_rolling_spring[c];
}

void k_clear_buckets(uint b) {
  if (b > PC.table_size + 1u) return;
  B_cell_start[b] = 0u;
  if (b <= PC.table_size) B_cell_fill[b] = 0u;
}

// Body-level broad phase (clumps, kFlagBodyBroadPhase), by parts: each body is cut across its
// longest axis into parts (Model, add_body_parts), each with a bounding sphere. At the start of a
// rebuild each part lists the parts of other bodies its sphere meets, widened by the skin
// (part_near: a body's own bounding sphere first, then its parts), and a sub-sphere walks the grid
// only when it meets one of its part's listed spheres (sub_may_pair; else it is in no bucket
// either), and tests only the walls its part's sphere may meet (part_walls). A long body's bounding sphere (a 10 x 80 mm stalk's is
// 40 mm for 1 mm spheres) meets every neighbour's in a heap; its parts' (5-6 mm) meet a few, and
// a sub-sphere on the far side of its body meets none. The same list as without it: only pairs
// that near_pair would reject are skipped. Each body tests every other one, so the host enables it
// only where bodies are few against their sub-spheres (Model, choose_neighbour_search).

// The largest coordinate of x, for the rounding slack of a float distance test.
float coordinate_size(vec3 x) { return max(abs(x.x), max(abs(x.y), abs(x.z))); }

// True when spheres (a, ra) and (b, rb) come within the skin of each other, or nearly: positions
// placed from a body carry a few float roundings of their coordinates and of the body-frame
// offsets (body_place, part_place), so a slack of 1e-5 of both keeps the test conservative.
bool spheres_may_meet(vec3 a, float ra, vec3 b, float rb) {
  precise vec3 d = a - b;
  precise float size = ((coordinate_size(a) + coordinate_size(b)) + ra) + rb;
  precise float reach = ((ra + rb) + PC.skin) + 1e-5f * size;
  return dot3(d, d) < reach * reach;
}

// Part p's bounding sphere in the world, where its body is now.
void k_part_place(uint p) {
  if (p >= PC.n_parts) return;
  vec4 local = B_parts[p].local;
  uint b = B_parts[p].info.x;
  vec3 r = quat_rotate(B_bodies[b].quat, xyz(local));
  precise vec3 c = xyz(B_bodies[b].pos) + r;
  B_parts[p].world = vec4(c, local.w);
}

// False only when no sphere inside (c, radius) can come within `margin` of wall ws as
// wall_contact sees it: from a plane, a triangle or a rectangle (up to 2 margins beyond its edge)
// farther than radius + 2 margins; from a cylinder's surface radially or beyond its ends. With a
// slack for the float roundings of the placed positions, as spheres_may_meet.
bool part_may_meet_wall(WallState ws, vec3 c, float radius, float margin) {
  precise vec3 rel = c - xyz(ws.p0);
  vec3 dir = xyz(ws.p1);
  precise float size = (coordinate_size(c) + coordinate_size(xyz(ws.p0))) + radius;
  precise float reach = (radius + 2.0f * margin) + 1e-4f * size;
  uint type = ws.info.x;
  if (type == kWallPlane) return abs(dot3(rel, dir)) < reach;
  if (type == kWallRectangle) {
    precise float h = dot3(rel, dir);
    precise float du = max(abs(dot3(rel, xyz(ws.p2))) - ws.p2.w, 0.0f);
    precise float dv = max(abs(dot3(rel, xyz(ws.p3))) - ws.p3.w, 0.0f);
    return (h * h + du * du) + dv * dv < reach * reach;
  }
  if (type == kWallTriangle) {
    uint feature = kFeatureFace;
    precise vec3 d = c - closest_on_triangle(c, xyz(ws.p0), xyz(ws.p1), xyz(ws.p2), feature);
    return dot3(d, d) < reach * reach;
  }
  precise float s = dot3(rel, dir);  // a cylinder: its axis from p0 along dir for vel.w
  if (s < -reach || s > ws.vel.w + reach) return false;
  precise float d = length3(rel - scale3(dir, s));
  return d > ws.p1.w - reach && d < ws.p1.w + reach;
}

// The walls (bit w of the first 32) sub-sphere i's part may meet, as part_near found them at
// this rebuild; every wall without the body broad phase.
uint part_walls(uint i) {
  if ((PC.flags & kFlagBodyBroadPhase) == 0u) return 0xffffffffu;
  return B_parts[B_subs[i].info.z].info.w;
}

// Lists, for each part of body b, the parts of other bodies it may meet, by index, and the walls
// (of the first 32) its sphere may meet (info.w). Bodies whose
// bounding spheres miss b's are skipped whole: no sub-sphere of b can pair with theirs (a part's
// sphere may reach beyond its body's, but its sub-spheres do not). A body's parts are consecutive,
// so the walk over parts steps a body at a time.
void k_part_near(uint b) {
  if (b >= PC.n_bodies) return;
  uint first = B_subs[slot_of(B_bodies[b].spheres.x)].info.y;
  uint end = first + B_parts[first].info.y;
  for (uint p = first; p < end; ++p) {
    B_parts[p].near_count = 0u;
    vec4 cp = B_parts[p].world;
    uint walls = 0u;
    for (uint w = 0u; w < min(PC.n_walls, 32u); ++w)
      if (part_may_meet_wall(wall_at(w), xyz(cp), cp.w, PC.skin)) walls = walls | (1u << w);
    B_parts[p].info.w = walls;
  }
  vec3 cb = xyz(B_bodies[b].pos);
  float rb = uintBitsToFloat(B_parts[first].info.z);
  uint q = 0u;
  while (q < PC.n_parts) {
    uvec4 info = B_parts[q].info;  // q is body info.x's first part
    uint next = q + info.y;
    vec3 co = xyz(B_bodies[info.x].pos);
    float ro = uintBitsToFloat(info.z);
    if (info.x != b && spheres_may_meet(cb, rb, co, ro)) {
      for (uint p = first; p < end; ++p) {
        vec4 cp = B_parts[p].world;
        if (!spheres_may_meet(xyz(cp), cp.w, co, ro)) continue;
        uint count = B_parts[p].near_count;
        for (uint k = q; k < next; ++k) {
          vec4 ck = B_parts[k].world;
          if (!spheres_may_meet(xyz(cp), cp.w, xyz(ck), ck.w)) continue;
          if (count < kPartNearSlots) B_parts[p].near[count] = k;
          count = count + 1u;
        }
        B_parts[p].near_count = count;
      }
    }
    q = next;
  }
}

// False when sub-sphere i meets no part its own part listed (kFlagBodyBroadPhase): i then has
// no particle partner, and is left out of the buckets too. A part that met more than it could
// list lets every sub-sphere walk.
bool sub_may_pair(uint i) {
  if ((PC.flags & kFlagBodyBroadPhase) == 0u) return true;
  uint p = B_subs[i].info.z;
  uint count = B_parts[p].near_count;
  if (count > kPartNearSlots) return true;
  vec4 pi = B_pos[i];
  for (uint k = 0u; k < count; ++k) {
    vec4 c = B_parts[B_parts[p].near[k]].world;
    if (spheres_may_meet(xyz(pi), pi.w, xyz(c), c.w)) return true;
  }
  return false;
}

ivec3 cell_of_position(vec3 x, float inv_cell) {
  return ivec3(cell_coord(x.x, inv_cell), cell_coord(x.y, inv_cell), cell_coord(x.z, inv_cell));
}

// A sub-sphere that meets no other body (sub_may_pair) goes in no bucket: no walk would keep it.
void k_bucket_count(uint i) {
  if (i >= PC.n_particles) return;
  vec4 p = B_pos[i];
  B_pos_at_build[i] = p;
  if (!sub_may_pair(i)) {
    B_cell_of[i] = kNoBucket;
    return;
  }
  ivec3 c = cell_of_position(xyz(p), PC.inv_cell);
  uint h = p.w > PC.large_radius ? PC.table_size : cell_hash(c.x, c.y, c.z, PC.table_size);
  B_cell_of[i] = h;
  atomicAdd(B_cell_start[h], 1u);
}

void k_bucket_scatter(uint i) {
  if (i >= PC.n_particles) return;
  uint h = B_cell_of[i];
  if (h == kNoBucket) return;
  uint slot = B_cell_start[h] + atomicAdd(B_cell_fill[h], 1u);
  B_sorted[slot] = i;
}

// Insertion sort of one bucket by global id: the scatter's order depends on thread timing.
void k_bucket_sort(uint b) {
  if (b > PC.table_size) return;
  uint begin = B_cell_start[b];
  uint end = B_cell_start[b + 1u];
  for (uint k = begin + 1u; k < end; ++k) {
    uint slot = B_sorted[k];
    uint id = global_id(slot);
    uint m = k;
    while (m > begin && global_id(B_sorted[m - 1u]) > id) {
      B_sorted[m] = B_sorted[m - 1u];
      m = m - 1u;
    }
    B_sorted[m] = slot;
  }
}

// True when j is within the skin of touching i and `owned`, with no branch on `owned`: a branch
// on the ids mispredicted on half the near pairs, whose ids fall either side of i's at random.
bool near_owned_pair(vec4 pi, vec4 pj, float skin, bool owned) {
  precise vec3 d = xyz(pi) - xyz(pj);
  precise float reach = (pi.w + pj.w + skin) * float(owned);  // x 1: the same reach; x 0: none
  return dot3(d, d) < reach * reach;
}

// True when j is a neighbour candidate of i: within the skin of touching.
bool near_pair(vec4 pi, vec4 pj, float skin) { return near_owned_pair(pi, pj, skin, true); }

// Adds partner number k to i's row (which starts at `base`), keeping the row sorted by partner
// id (partner_key): the gathers then sum touching contacts in the same order whatever else the
// list holds, so results do not depend on the skin, the cell size or when the list is rebuilt. Carries the
// pair's history over from i's old row (zero for a new pair). Entries beyond the capacity are
// counted but not written (overflow: the batch is redone with a larger list).
void write_candidate(uint base, uint k, uint i, uint partner, uint old_begin, uint old_end) {
  uint slot = base + k;
  if (slot >= PC.capacity) return;
  bool springs = (PC.flags & kFlagRollingSpring) != 0u;
  B_owner[slot] = i;
  uint key = partner_key(partner);
  while (slot > base && partner_key(B_partner[slot - 1u]) > key) {
    B_partner[slot] = B_partner[slot - 1u];
    B_history[slot] = B_history[slot - 1u];
    if (springs) B_rolling_spring[slot] = B_rolling_spring[slot - 1u];
    slot = slot - 1u;
  }
  B_partner[slot] = partner;
  uint from = 0xffffffffu;  // the old entry: a pick, where a branch mispredicted at every match
  for (uint o = old_begin; o < old_end; ++o) from = B_old_partner[o] == partner ? o : from;
  B_history[slot] = from != 0xffffffffu ? B_old_history[from] : vec4(0.0f);
  if (springs) B_rolling_spring[slot] = from != 0xffffffffu ? B_rolling_spring[PC.capacity + from] : vec4(0.0f);
}

// Candidate k of i found by a walk: written to i's row in a fill walk; in the count walk kept in
// i's candidate slots (the first kCandidateSlots), so contact_fill need not walk again.
void emit_candidate(bool fill, uint base, uint k, uint i, uint partner, uint old_begin, uint old_end) {
  if (fill) write_candidate(base, k, i, partner, old_begin, old_end);
  else if (k < kCandidateSlots) B_candidates[i * kCandidateSlots + k] = partner;
}

// A fixed particle (a fixed sphere, or a sub-sphere of a fixed body) has 1/mass = 0: it takes
// part in contacts with moving particles as an infinite mass, and never moves.
bool is_fixed(uint i) { return B_vel[i].w == 0.0f; }

// True when particles i and j never form a contact: sub-spheres of one body (none inside a
// clump), or two fixed particles (neither can move; their m* would be infinite).
bool no_contact(uint i, uint j) {
  if ((PC.flags & kFlagBodies) != 0u && B_subs[i].info.x == B_subs[j].info.x) return true;
  return is_fixed(i) && is_fixed(j);
}

// The lowest global id a small particle i pairs with on the grid: the pair belongs to the lower
// id, and a clump's sub-spheres (consecutive ids) never pair with each other.
uint first_partner_id(uint i) {
  if ((PC.flags & kFlagBodies) == 0u) return global_id(i) + 1u;
  uvec4 range = B_bodies[B_subs[i].info.x].spheres;
  return range.x + range.y;
}

// The first place in bucket [begin, end) (sorted by id) holding an id >= lowest: a binary search,
// so a walk skips the ids it would reject (half of them; in a clump, its own sub-spheres). The
// bucket's two ends first, two loads independent of each other: they settle a bucket of one or
// two spheres (most of a bed's) without the search's chain of loads.
uint first_slot_from(uint begin, uint end, uint lowest) {
  if (begin == end || global_id(B_sorted[end - 1u]) < lowest) return end;
  if (global_id(B_sorted[begin]) >= lowest) return begin;
  uint lo = begin + 1u;  // begin's id is below lowest, end - 1's is not
  uint hi = end - 1u;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (global_id(B_sorted[mid]) < lowest) lo = mid + 1u;
    else hi = mid;
  }
  return lo;
}

// Sphere j of a slot that passed the id and distance tests: a candidate of i unless its cell is
// not one of the row's (a hash collision). Returns the candidates counted, from k.
uint keep_in_row(uint i, uint j, vec4 pj, int x0, int x1, ivec3 c, bool fill, uint base, uint k, uint old_begin,
                 uint old_end) {
  ivec3 cj = cell_of_position(xyz(pj), PC.inv_cell);
  if (cj.y != c.y || cj.z != c.z || cj.x < x0 || cj.x > x1) return k;
  emit_candidate(fill, base, k, i, j, old_begin, old_end);
  return k + 1u;
}

// The spheres of sorted slots [begin, end) that sit in cells (x0 .. x1, c.y, c.z) and are
// candidates of i: ids from `lowest` (a lower id owns the pair, or j is in i's clump), within the
// skin. A row of three cells takes consecutive buckets (cell_hash), so one run of slots holds it,
// in the order a cell-by-cell walk would meet them (each bucket sorted by id); a sphere of another
// cell that shares a bucket (a hash collision) is left out by its cell. The id and distance tests
// reject most of the spheres in 27 cells, and cost less than the cell's three floors (the same
// pairs pass in either order). Returns the candidates counted, from k.
uint walk_cells(uint i, vec4 pi, int x0, int x1, ivec3 c, uint begin, uint end, uint lowest, bool i_fixed, bool fill,
                uint base, uint k, uint old_begin, uint old_end) {
  if ((PC.flags & kFlagBodies) != 0u) {
    // A clump's cells hold runs of one body's sub-spheres (consecutive ids): the id test first,
    // predicted along a run, skips them unread.
    for (uint s = begin; s < end; ++s) {
      uint j = B_sorted[s];
      if (global_id(j) < lowest) continue;
      if (i_fixed && is_fixed(j)) continue;
      vec4 pj = B_pos[j];
      if (!near_pair(pi, pj, PC.skin)) continue;
      k = keep_in_row(i, j, pj, x0, x1, c, fill, base, k, old_begin, old_end);
    }
    return k;
  }
  // Free spheres' ids fall either side of i's at random: both tests before one branch.
  for (uint s = begin; s < end; ++s) {
    uint j = B_sorted[s];
    vec4 pj = B_pos[j];
    if (!near_owned_pair(pi, pj, PC.skin, global_id(j) >= lowest) || (i_fixed && is_fixed(j))) continue;
    k = keep_in_row(i, j, pj, x0, x1, c, fill, base, k, old_begin, old_end);
  }
  return k;
}

// The spheres of the large bucket (sorted slots [begin, end), radii above PC.large_radius) that are
// candidates of i: ids from `lowest` (walk_neighbours: 0 for a small i, which owns its pairs with
// them; past i's own for a large one), within the skin, not two sides of one body or two fixed
// spheres. Returns the candidates counted, from k.
uint walk_large(uint i, vec4 pi, uint lowest, uint begin, uint end, bool fill, uint base, uint k, uint old_begin,
                uint old_end) {
  for (uint s = begin; s < end; ++s) {
    uint j = B_sorted[s];
    if (global_id(j) < lowest || !near_pair(pi, B_pos[j], PC.skin) || no_contact(i, j)) continue;
    emit_candidate(fill, base, k, i, j, old_begin, old_end);
    k = k + 1u;
  }
  return k;
}

// Wall w as the k-th candidate of sphere i when it comes within the skin of touching as
// wall_contact sees it (and i's part may meet it: part_walls); returns the candidates so far.
uint wall_candidate(uint i, vec4 pi, uint w, uint near_walls, bool fill, uint base, uint k, uint old_begin,
                    uint old_end) {
  if (w < 32u && (near_walls & (1u << w)) == 0u) return k;  // out of reach of i's part
  if (!wall_within_skin(i, pi, w)) return k;
  emit_candidate(fill, base, k, i, PC.n_particles + w, old_begin, old_end);
  return k + 1u;
}

// The wall grid (docs/engineering.md, "The wall grid"; host/engine/wall_grid.h): the host lists
// each still triangle under every cell of the particle grid from which a small sphere's centre
// can come within the skin of touching it (with a slack for the roundings); the other walls
// (planes, cylinders, rectangles, moving walls) are on a list every sphere tests. B_wall_grid
// holds, for T = PC.wall_table_size: [0, T) the starts of the buckets of cell_hash, [T] the start
// of that list and [T + 1] its end; a bucket holds its cells one after the other, each as
// (x, y, z, count, its walls ascending). Candidates are written in rows sorted by partner, so
// the order in which a walk finds them changes no byte, and a wall the grid leaves out is one
// wall_contact rejects: the list is the one every wall tested gives. Spheres above
// PC.large_radius, beyond the grid's reach, test every wall, as every sphere does without a grid
// (T = 0).
uint walk_walls(uint i, vec4 pi, ivec3 ci, bool large, bool fill, uint base, uint k, uint old_begin, uint old_end) {
  uint near_walls = part_walls(i);
  uint t = PC.wall_table_size;
  if (t == 0u || large) {
    for (uint w = 0u; w < PC.n_walls; ++w) k = wall_candidate(i, pi, w, near_walls, fill, base, k, old_begin, old_end);
    return k;
  }
  uint end = B_wall_grid[t + 1u];
  for (uint s = B_wall_grid[t]; s < end; ++s)
    k = wall_candidate(i, pi, B_wall_grid[s], near_walls, fill, base, k, old_begin, old_end);
  uint h = cell_hash(ci.x, ci.y, ci.z, t);
  end = B_wall_grid[h + 1u];
  uint s = B_wall_grid[h];
  while (s < end) {  // the bucket's cells: i's own, if listed, and others of the same hash
    uint count = B_wall_grid[s + 3u];
    uint first = s + 4u;
    s = first + count;
    if (int(B_wall_grid[first - 4u]) != ci.x || int(B_wall_grid[first - 3u]) != ci.y ||
        int(B_wall_grid[first - 2u]) != ci.z)
      continue;
    for (uint e = first; e < s; ++e)
      k = wall_candidate(i, pi, B_wall_grid[e], near_walls, fill, base, k, old_begin, old_end);
    return k;
  }
  return k;
}

// Walks the 27 cells around i in a fixed order (small particles only), then the large bucket,
// then the walls. With `fill`, writes partners, owners and carried histories from `base`;
// returns the number of candidates.
uint walk_neighbours(uint i, bool fill, uint base) {
  vec4 pi = B_pos[i];
  bool large = pi.w > PC.large_radius;
  ivec3 ci = cell_of_position(xyz(pi), PC.inv_cell);
  uint k = 0u;
  uint old_begin = 0u;
  uint old_end = 0u;
  if (fill) {
    old_begin = B_old_row_start[i];
    old_end = min(B_old_row_start[i + 1u], B_control[kCtlOldContacts]);
  }
  uint lowest = large ? 0u : first_partner_id(i);
  bool i_fixed = is_fixed(i);
  bool pairs = sub_may_pair(i);
  for (int dz = (large || !pairs) ? 2 : -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      ivec3 row = ivec3(ci.x, ci.y + dy, ci.z + dz);
      uint h0 = cell_hash(ci.x - 1, row.y, row.z, PC.table_size);
      if (h0 + 2u < PC.table_size) {  // the row's three cells: buckets h0 .. h0 + 2, one run of slots
        k = walk_row(i, pi, ci.x - 1, ci.x + 1, row, B_cell_start[h0], B_cell_start[h0 + 3u], lowest, i_fixed, fill,
                     base, k, old_begin, old_end);
        continue;
      }
      for (int x = ci.x - 1; x <= ci.x + 1; ++x) {  // the row wraps around the table's end: cell by cell
        uint h = cell_hash(x, row.y, row.z, PC.table_size);
        uint end = B_cell_start[h + 1u];
        k = walk_row(i, pi, x, x, row, first_slot_from(B_cell_start[h], end, lowest), end, lowest, i_fixed, fill, base,
                     k, old_begin, old_end);
      }
    }
  }
  if (pairs)
    k = walk_large_bucket(i, pi, large ? global_id(i) + 1u : 0u, B_cell_start[PC.table_size],
                          B_cell_start[PC.table_size + 1u], fill, base, k, old_begin, old_end);
  if (i_fixed) return k;  // a wall cannot push a fixed particle either
  return walk_walls(i, pi, ci, large, fill, base, k, old_begin, old_end);
}

// Counts contacts per owner into row_start (scanned in place next) and resets the transposed
// counters, which the same rebuild fills later.
void k_contact_count(uint i) {
  if (i > PC.n_particles) return;
  B_row_start[i] = i < PC.n_particles ? walk_neighbours(i, false, 0u) : 0u;
  B_trans_start[i] = 0u;
  if (i < PC.n_particles) B_trans_fill[i] = 0u;
}

// Writes i's row from the candidates contact_count kept, or walks again when it found more.
void k_contact_fill(uint i) {
  if (i >= PC.n_particles) return;
  uint base = B_row_start[i];
  uint count = B_row_start[i + 1u] - base;
  if (count > kCandidateSlots) {
    walk_neighbours(i, true, base);
    return;
  }
  uint old_begin = B_old_row_start[i];
  uint old_end = min(B_old_row_start[i + 1u], B_control[kCtlOldContacts]);
  for (uint k = 0u; k < count; ++k)
    write_candidate(base, k, i, B_candidates[i * kCandidateSlots + k], old_begin, old_end);
}

void k_transpose_count(uint c) {
  if (c >= B_control[kCtlContacts]) return;
  uint p = B_partner[c];
  if (p < PC.n_particles) atomicAdd(B_trans_start[p], 1u);
}

void k_transpose_fill(uint c) {
  if (c >= B_control[kCtlContacts]) return;
  uint p = B_partner[c];
  if (p >= PC.n_particles) return;
  uint slot = B_trans_start[p] + atomicAdd(B_trans_fill[p], 1u);
  B_trans_list[slot] = c;
}

// Sorts i's transposed row by the owner's global id (one contact per owner), so a gather sums it
// in the same order whatever the slots.
void k_transpose_sort(uint i) {
  if (i >= PC.n_particles) return;
  uint begin = B_trans_start[i];
  uint end = B_trans_start[i + 1u];
  for (uint k = begin + 1u; k < end; ++k) {
    uint c = B_trans_list[k];
    uint owner = global_id(B_owner[c]);
    uint m = k;
    while (m > begin && global_id(B_owner[B_trans_list[m - 1u]]) > owner) {
      B_trans_list[m] = B_trans_list[m - 1u];
      m = m - 1u;
    }
    B_trans_list[m] = c;
  }
}

// Called by the scan of the rows (one invocation, after the scan): the list's size and the
// indirect sizes of the per-contact kernels.
void k_rows_scanned(uint unused) {
  uint total = B_row_start[PC.n_particles];
  if (total > PC.capacity) B_control[kCtlOverflow] = 1u;
  if (total > B_control[kCtlMaxContacts]) B_control[kCtlMaxContacts] = total;
  uint used = min(total, PC.capacity);
  B_control[kCtlContacts] = used;
  set_groups(kCtlArgsContacts, groups_for(used, PC.workgroup));
  set_groups(kCtlArgsNewContacts, groups_for(used, PC.workgroup));
}

#endif
