// The CPU twin's neighbour walk with each row of cells' slots tested in SIMD lanes (Highway,
// chosen at run time as for the contact lanes). In a pour the list is rebuilt every few steps
// and the scalar walk was a third of the step: a branch per slot, mispredicted at every passing
// candidate. Here a pass over the sorted slots first copies their positions, radii and global
// ids into five arrays (Buffers::walk_rows), so that a row's slots load in order with no gather;
// the lanes then do near_owned_pair's test (its operations in its order) and each slot that
// passes goes on through the shared text in slot order (keep_in_row in a row of cells, as
// walk_cells; no_contact in the large bucket, as walk_large, which every sphere walks whole): the
// same candidates in the same order (tests/engine/test_neighbour_walk.cpp).
#pragma once
#include <cstddef>
#include <cstdint>

namespace repose::gpu {

struct Kernels;

// Floats Buffers::walk_rows needs for n particles.
size_t walk_rows_floats(size_t n);
// Sorted slots [begin, end)'s rows into Buffers::walk_rows (after bucket_sort, before the walk).
void fill_walk_rows(Kernels& k, uint64_t begin, uint64_t end);
// k_contact_count(i) for every i in [begin, end), each row of cells walked in lanes.
void contact_count_lanes(Kernels& k, uint64_t begin, uint64_t end);
// k_contact_fill(i) for every i in [begin, end), each row placed and its histories found in lanes.
void contact_fill_lanes(Kernels& k, uint64_t begin, uint64_t end);

}  // namespace repose::gpu
