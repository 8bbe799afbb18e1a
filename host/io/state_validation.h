// What a state must be before a simulation takes it. A damaged or forged state file would
// otherwise crash the engine (an index past an array), hang it (an overflow flag, an absurd list
// size) or run silently wrong (a negative radius, a particle frozen by 1/mass = 0). Each check
// returns "" or the first problem, worded for the file's reader ("partner[0] = 4294967295 ...").
#pragma once
#include <cstdint>
#include <string>

#include "engine/backend.h"
#include "engine/model.h"

namespace repose {

// The state on its own (any file read_state_file reads): every number finite, radii > 0,
// positions a float can resolve; the contact list's rows, partners and owners, and its transposed
// index, exactly as the engine builds them; bodies covering the particles; the control words of
// a finished batch at step `step`, time `time`.
std::string state_problem(const HostState& s, uint64_t step, double time);

// The state against the case it is to continue: the same counts, partners among its walls, a
// list size the case can need, and the constants the case sets (radii, 1/mass, 1/inertia, the
// bodies' masses, inertias and spheres) bit for bit.
std::string state_misfit(const HostState& s, const Model& model);

}  // namespace repose
