#include "diagnosis/heap_measures.h"

namespace repose {

const std::vector<std::string>& heap_measure_names() {
  static const std::vector<std::string> names = {"repose_angle", "bed_height", "heap_height", "runout",
                                                 "profile_convexity"};
  return names;
}

std::map<std::string, double> heap_measures(const ReposeResult& heap, const std::string& heap_side) {
  std::vector<const SlopeProfile*> sides;
  if (heap_side != "right") sides.push_back(&heap.profile.left);
  if (heap_side != "left") sides.push_back(&heap.profile.right);
  double runout = 0, convexity = 0;
  for (const SlopeProfile* s : sides) {
    runout += s->runout / double(sides.size());
    if (s->valid) convexity += s->convexity / double(sides.size());
  }
  return {{"repose_angle", heap.angle_deg},
          {"bed_height", heap.bed_height},
          {"heap_height", heap.profile.height},
          {"runout", runout},
          {"profile_convexity", convexity}};
}

}  // namespace repose
