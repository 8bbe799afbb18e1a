// Which grains are the heap: those resting on the floor, directly or through grains that touch
// each other. A heap poured from a hopper that stays in place leaves grains on the hopper's cone
// and on its gate, above the heap and apart from it; a photograph of the heap (the studies
// measure one) does not show them, but a front view of every grain would draw them as spikes on
// the heap's outline (the million-grain heap's 122 such grains turned its 16 deg slopes into
// 42 deg).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/sphere.h"

namespace repose {

// Two grains touch when their centres are no farther apart than their radii and a tenth of the
// smaller one (a settled heap's contacts overlap; the tenth keeps a contact opened for a moment);
// a grain rests on the floor when its bottom is within a quarter of its radius of floor_z.
inline constexpr double kTouchGap = 0.1;
inline constexpr double kFloorGap = 0.25;

// For each sphere: whether it is connected to the floor through touching spheres. `bodies`
// (empty, or one value per sphere): spheres with the same value are one rigid body, which rests
// or not as a whole (a cabbage's leaf veins need not touch its core). The same for any order of
// the spheres.
std::vector<bool> resting_on_floor(const std::vector<Sphere>& spheres, double floor_z,
                                   const std::vector<uint32_t>& bodies = {});

// The same, applied: keeps the resting spheres (in their order) and returns how many it left out.
size_t keep_resting(std::vector<Sphere>& spheres, double floor_z, const std::vector<uint32_t>& bodies = {});

}  // namespace repose
