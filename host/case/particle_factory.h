// Turns [[fill]] and [[lattice]] entries into spheres, deterministically: the same case and seed
// give the same spheres, bit for bit, with any standard library (random numbers are mapped from
// raw std::mt19937_64 draws by hand, never through std::uniform_*_distribution).
#pragma once
#include <cstdint>
#include <vector>

#include "case/case_spec.h"

namespace repose {

// A double uniform in [0, 1) from the top 53 bits of one raw 64-bit draw.
inline double unit_interval(uint64_t raw) { return double(raw >> 11) * 0x1.0p-53; }

// Checks the explicit spheres, then appends every [[lattice]] and then every sphere [[fill]]
// (each in file order) to spec.spheres, then every template fill to spec.bodies. Lattices come first because their sites are fixed, and the random
// fills can then pack around them. Call once, on a spec whose spheres are the explicit ones.
// Throws CaseError when explicit spheres overlap, a lattice site overlaps an earlier sphere, or
// a fill cannot place its count.
void expand_particles(CaseSpec& spec);

// Throws CaseError naming both entries (and their lines) for the first sphere, in order, that
// overlaps an earlier one. Touching spheres are allowed.
void check_no_overlaps(const std::vector<SphereSpec>& spheres);

// The lattice's sites inside its box, keeping a margin of one radius from every face, ordered
// by height (z), then y, then x; bcc interleaves its body-centre layers between corner layers.
std::vector<Vec3d> lattice_sites(const LatticeSpec& lattice);

// Appends lattice.max_count sites (all when 0) to spheres. Throws CaseError when a site overlaps
// a sphere already there, or when fewer sites fit than max_count asks for.
void append_lattice(const LatticeSpec& lattice, std::vector<SphereSpec>& spheres);

// Random sequential addition: each new sphere draws its radius, then tries random centres in the
// region (one radius from its boundary) until it overlaps no sphere already in `spheres`, up to
// kFillTriesPerSphere tries. Throws CaseError saying how many fitted when one finds no place.
// A fill of kFillInCellOrder spheres or more is then stored in the order of its cells (a Morton
// order of cells two radii wide) instead of the order it was placed in, which is random in space:
// spheres that touch are then near in memory, and the kernels gather their rows from the cache
// instead of from main memory. Smaller fills keep the placement order (and the bytes of every
// case written before the rule).
constexpr int kFillTriesPerSphere = 20000;
constexpr int kFillInCellOrder = 100000;
void append_fill(const FillSpec& fill, std::vector<SphereSpec>& spheres);

// The same for a template fill: bodies at random orientations and scales, none overlapping the
// spheres or bodies already in spec (sub-sphere against sub-sphere), the body's bounding sphere
// inside the region. Appends to spec.bodies.
constexpr int kFillTriesPerBody = 5000;
void append_body_fill(const FillSpec& fill, CaseSpec& spec);

// Bodies of a template lattice at its sites (cell edge per axis, one orientation, margins the
// oriented body's half-extents). Throws CaseError when a body overlaps a particle placed before.
void append_body_lattice(const LatticeSpec& lattice, CaseSpec& spec);

}  // namespace repose
