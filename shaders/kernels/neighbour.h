// Deterministic neighbour search and contact list (docs/engineering.md, neighbour search).
// A rebuild happens in a step when a particle moved more than half the skin since the last one
// (or max_interval steps passed); rebuild_args decides on the device and writes the indirect
// dispatch sizes of every rebuild kernel, zero when there is nothing to do, so the host records
// the same command stream every step. Atomics only count integers; every order that reaches a
// float result is fixed by sorting (buckets by particle id, transposed rows by contact index).
// Sizes spanning 10:1 (a clump's 160 mm core among 5 mm veins) would make cells as big as the
// largest sphere and full of small ones, so particles above PC.large_radius skip the grid: they
// share one extra bucket (index T) that every walk scans. A pair of a small and a large particle
// belongs to the small one's row, a pair of two large ones to the lower index.
#ifndef REPOSE_KERNELS_NEIGHBOUR_H
#define REPOSE_KERNELS_NEIGHBOUR_H

KFN(void, set_groups) uint word, uint groups) {
  B_control[word] = groups;
  B_control[word + 1u] = 1u;
  B_control[word + 2u] = 1u;
}

// One invocation: decide whether this step rebuilds the list.
KERNEL(k_rebuild_args) uint unused) {
  bool due = PC.max_interval > 0u && B_control[kCtlStepsSinceBuild] + 1u >= PC.max_interval;
  bool rebuild = B_control[kCtlNeedRebuild] != 0u || due || B_control[kCtlRebuildCount] == 0u;
  B_control[kCtlNeedRebuild] = 0u;
  B_control[kCtlRebuilding] = rebuild ? 1u : 0u;
  uint wg = PC.workgroup;
  if (rebuild) {
    B_control[kCtlStepsSinceBuild] = 0u;
    B_control[kCtlRebuildCount] = B_control[kCtlRebuildCount] + 1u;
    B_control[kCtlOldContacts] = B_control[kCtlContacts];
    set_groups(KB kCtlArgsParticles, groups_for(PC.n_particles + 1u, wg));
    set_groups(KB kCtlArgsBuckets, groups_for(PC.table_size + 2u, wg));
    set_groups(KB kCtlArgsOne, 1u);
    set_groups(KB kCtlArgsOldContacts, groups_for(B_control[kCtlContacts], wg));
  } else {
    B_control[kCtlStepsSinceBuild] = B_control[kCtlStepsSinceBuild] + 1u;
    set_groups(KB kCtlArgsParticles, 0u);
    set_groups(KB kCtlArgsBuckets, 0u);
    set_groups(KB kCtlArgsOne, 0u);
    set_groups(KB kCtlArgsOldContacts, 0u);
    set_groups(KB kCtlArgsNewContacts, 0u);
  }
}

// Keep the list being replaced (with its up-to-date histories) to carry histories over.
KERNEL(k_save_old_rows) uint i) {
  if (i > PC.n_particles) return;
  B_old_row_start[i] = B_row_start[i];
}
KERNEL(k_save_old_contacts) uint c) {
  if (c >= B_control[kCtlOldContacts]) return;
  B_old_partner[c] = B_partner[c];
  B_old_history[c] = B_history[c];
  if ((PC.flags & kFlagRollingSpring) != 0u) B_rolling_spring[PC.capacity + c] = B_rolling_spring[c];
}

KERNEL(k_clear_buckets) uint b) {
  if (b > PC.table_size + 1u) return;
  B_cell_start[b] = 0u;
  if (b <= PC.table_size) B_cell_fill[b] = 0u;
}

FN ivec3 cell_of_position(vec3 x, float inv_cell) {
  return ivec3(cell_coord(x.x, inv_cell), cell_coord(x.y, inv_cell), cell_coord(x.z, inv_cell));
}

KERNEL(k_bucket_count) uint i) {
  if (i >= PC.n_particles) return;
  vec4 p = B_pos[i];
  B_pos_at_build[i] = p;
  ivec3 c = cell_of_position(xyz(p), PC.inv_cell);
  uint h = p.w > PC.large_radius ? PC.table_size : cell_hash(c.x, c.y, c.z, PC.table_size);
  B_cell_of[i] = h;
  atomicAdd(B_cell_start[h], 1u);
}

KERNEL(k_bucket_scatter) uint i) {
  if (i >= PC.n_particles) return;
  uint h = B_cell_of[i];
  uint slot = B_cell_start[h] + atomicAdd(B_cell_fill[h], 1u);
  B_sorted[slot] = i;
}

// Insertion sort of one bucket by particle id: the scatter's order depends on thread timing.
KERNEL(k_bucket_sort) uint b) {
  if (b > PC.table_size) return;
  uint begin = B_cell_start[b];
  uint end = B_cell_start[b + 1u];
  for (uint k = begin + 1u; k < end; ++k) {
    uint id = B_sorted[k];
    uint m = k;
    while (m > begin && B_sorted[m - 1u] > id) {
      B_sorted[m] = B_sorted[m - 1u];
      m = m - 1u;
    }
    B_sorted[m] = id;
  }
}

// True when j is a neighbour candidate of i: within the skin of touching.
FN bool near_pair(vec4 pi, vec4 pj, float skin) {
  precise vec3 d = xyz(pi) - xyz(pj);
  precise float reach = pi.w + pj.w + skin;
  return dot3(d, d) < reach * reach;
}

// Writes list entry `slot` (i, partner), carrying the pair's history over from i's old row
// (zero for a new pair); slots beyond the capacity are counted but not written (overflow).
KFN(void, write_candidate) uint slot, uint i, uint partner, uint old_begin, uint old_end) {
  if (slot >= PC.capacity) return;
  B_partner[slot] = partner;
  B_owner[slot] = i;
  vec4 carried = vec4(0.0f);
  uint from = 0xffffffffu;
  for (uint o = old_begin; o < old_end; ++o)
    if (B_old_partner[o] == partner) {
      carried = B_old_history[o];
      from = o;
    }
  B_history[slot] = carried;
  if ((PC.flags & kFlagRollingSpring) != 0u)
    B_rolling_spring[slot] = from != 0xffffffffu ? B_rolling_spring[PC.capacity + from] : vec4(0.0f);
}

// True when particles i and j are sub-spheres of one body (no contact inside a clump).
KFN(bool, same_body) uint i, uint j) {
  return (PC.flags & kFlagBodies) != 0u && B_subs[i].info.x == B_subs[j].info.x;
}

// Walks the 27 cells around i in a fixed order (small particles only), then the large bucket,
// then the walls. With `fill`, writes partners, owners and carried histories from `base`;
// returns the number of candidates.
KFN(uint, walk_neighbours) uint i, bool fill, uint base) {
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
  for (int dz = large ? 2 : -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 cc = ivec3(ci.x + dx, ci.y + dy, ci.z + dz);
        uint h = cell_hash(cc.x, cc.y, cc.z, PC.table_size);
        uint end = B_cell_start[h + 1u];
        for (uint s = B_cell_start[h]; s < end; ++s) {
          uint j = B_sorted[s];
          if (j <= i || same_body(KB i, j)) continue;
          vec4 pj = B_pos[j];
          ivec3 cj = cell_of_position(xyz(pj), PC.inv_cell);
          if (cj.x != cc.x || cj.y != cc.y || cj.z != cc.z) continue;  // a hash collision
          if (!near_pair(pi, pj, PC.skin)) continue;
          if (fill) write_candidate(KB base + k, i, j, old_begin, old_end);
          k = k + 1u;
        }
      }
    }
  }
  uint large_end = B_cell_start[PC.table_size + 1u];
  for (uint s = B_cell_start[PC.table_size]; s < large_end; ++s) {
    uint j = B_sorted[s];
    if (j == i || (large && j < i) || same_body(KB i, j)) continue;
    if (!near_pair(pi, B_pos[j], PC.skin)) continue;
    if (fill) write_candidate(KB base + k, i, j, old_begin, old_end);
    k = k + 1u;
  }
  for (uint w = 0u; w < PC.n_walls; ++w) {
    WallState ws = B_walls[PC.wall_slot * PC.n_walls + w];
    vec3 n;
    float overlap;
    if (!wall_contact(ws, xyz(pi), pi.w, PC.skin, n, overlap)) continue;
    if (fill) write_candidate(KB base + k, i, PC.n_particles + w, old_begin, old_end);
    k = k + 1u;
  }
  return k;
}

// Counts contacts per owner into row_start (scanned in place next) and resets the transposed
// counters, which the same rebuild fills later.
KERNEL(k_contact_count) uint i) {
  if (i > PC.n_particles) return;
  B_row_start[i] = i < PC.n_particles ? walk_neighbours(KB i, false, 0u) : 0u;
  B_trans_start[i] = 0u;
  if (i < PC.n_particles) B_trans_fill[i] = 0u;
}

KERNEL(k_contact_fill) uint i) {
  if (i >= PC.n_particles) return;
  walk_neighbours(KB i, true, B_row_start[i]);
}

KERNEL(k_transpose_count) uint c) {
  if (c >= B_control[kCtlContacts]) return;
  uint p = B_partner[c];
  if (p < PC.n_particles) atomicAdd(B_trans_start[p], 1u);
}

KERNEL(k_transpose_fill) uint c) {
  if (c >= B_control[kCtlContacts]) return;
  uint p = B_partner[c];
  if (p >= PC.n_particles) return;
  uint slot = B_trans_start[p] + atomicAdd(B_trans_fill[p], 1u);
  B_trans_list[slot] = c;
}

KERNEL(k_transpose_sort) uint i) {
  if (i >= PC.n_particles) return;
  uint begin = B_trans_start[i];
  uint end = B_trans_start[i + 1u];
  for (uint k = begin + 1u; k < end; ++k) {
    uint c = B_trans_list[k];
    uint m = k;
    while (m > begin && B_trans_list[m - 1u] > c) {
      B_trans_list[m] = B_trans_list[m - 1u];
      m = m - 1u;
    }
    B_trans_list[m] = c;
  }
}

// Called by the scan of the rows (one invocation, after the scan): the list's size and the
// indirect sizes of the per-contact kernels.
KERNEL(k_rows_scanned) uint unused) {
  uint total = B_row_start[PC.n_particles];
  if (total > PC.capacity) B_control[kCtlOverflow] = 1u;
  if (total > B_control[kCtlMaxContacts]) B_control[kCtlMaxContacts] = total;
  uint used = min(total, PC.capacity);
  B_control[kCtlContacts] = used;
  set_groups(KB kCtlArgsContacts, groups_for(used, PC.workgroup));
  set_groups(KB kCtlArgsNewContacts, groups_for(used, PC.workgroup));
}

#endif
