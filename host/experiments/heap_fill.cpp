#include "experiments/heap_fill.h"

#include <cmath>

#include "case/case_error.h"
#include "case/particle_factory.h"

namespace repose {

namespace {

constexpr double kRaiseStep = 0.25;  // of the fill box's height, per try
constexpr int kRaiseSteps = 4;       // up to twice its height

// The axis gravity points along (its largest component) and whether it points down that axis.
int gravity_axis(const CaseSpec& spec, bool& down) {
  int axis = 2;
  for (int a = 0; a < 3; ++a)
    if (std::abs(spec.gravity[a]) > std::abs(spec.gravity[axis])) axis = a;
  down = spec.gravity[axis] <= 0;
  return axis;
}

// Raises every sphere box fill's far side from gravity by `fraction` of its extent along gravity.
void raise_fill_boxes(CaseSpec& spec, const CaseSpec& original, double fraction) {
  bool down = true;
  int axis = gravity_axis(spec, down);
  for (size_t k = 0; k < spec.fills.size(); ++k) {
    FillSpec& f = spec.fills[k];
    const FillSpec& o = original.fills[k];
    if (f.template_index >= 0 || f.shape != FillSpec::Shape::Box) continue;
    double extent = o.box_max[axis] - o.box_min[axis];
    if (down) f.box_max[axis] = o.box_max[axis] + fraction * extent;
    else f.box_min[axis] = o.box_min[axis] - fraction * extent;
  }
}

}  // namespace

HeapFill fill_heap(CaseSpec& spec) {
  const CaseSpec original = spec;
  HeapFill how;
  std::string first_problem;
  try {
    expand_particles(spec);
    return how;
  } catch (const CaseError& e) {
    first_problem = e.what();
  }
  how.fallback = true;
  for (int step = 0; step <= kRaiseSteps; ++step) {
    spec = original;
    for (FillSpec& f : spec.fills) f.largest_first = true;
    how.raised = kRaiseStep * step;
    if (step > 0) raise_fill_boxes(spec, original, how.raised);
    try {
      expand_particles(spec);
      return how;
    } catch (const CaseError&) {
    }
  }
  spec = original;
  throw HeapFillError("the grains do not fit the fill box even placed largest first in a box raised to " +
                      std::to_string(1 + kRaiseStep * kRaiseSteps).substr(0, 3) + " times its height (" +
                      first_problem + ")");
}

}  // namespace repose
