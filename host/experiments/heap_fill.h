// The grains of a diagnosed heap for one model and replicate. A candidate that makes grains larger
// (a size spread) can ask for more room than random sequential addition finds in the case's fill
// box ("only 248 of the 250 spheres fit"). So a fill that fails is placed again, largest grain
// first (the big grains find room while the box is empty, the small ones fill the gaps), and if
// that fails too, largest first in the box raised against gravity by a quarter of its height at a
// time, up to twice its height: the same walls around it, only its top higher (the grains fall a
// little further before the rig's lift). The case's own fill is used whenever it succeeds, so a
// model that fits keeps its bytes. Only a count that fits none of these is refused, by a
// HeapFillError that says so; the diagnosis then reports the candidate untested with that reason.
#pragma once
#include <stdexcept>
#include <string>

#include "case/case_spec.h"

namespace repose {

struct HeapFillError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct HeapFill {
  bool fallback = false;  // the case's own fill failed: placed largest first
  double raised = 0;      // fraction of its height the fill box was raised by (0, 0.25, ... 1)
};

// Expands spec's particles (expand_particles) as above. The spec's spheres must be the explicit
// ones (none, for a diagnosed heap).
HeapFill fill_heap(CaseSpec& spec);

}  // namespace repose
