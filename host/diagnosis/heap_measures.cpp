#include "diagnosis/heap_measures.h"

namespace repose {

const std::vector<std::string>& heap_measure_names() {
  static const std::vector<std::string> names = {"repose_angle", "bed_height", "heap_height", "runout",
                                                 "profile_convexity"};
  return names;
}

std::map<std::string, double> heap_measures(double angle_deg, double bed_height, const HeapProfile& profile,
                                            const std::string& heap_side) {
  std::vector<const SlopeProfile*> sides;
  if (heap_side != "right") sides.push_back(&profile.left);
  if (heap_side != "left") sides.push_back(&profile.right);
  double runout = 0, convexity = 0;
  for (const SlopeProfile* s : sides) {
    runout += s->runout / double(sides.size());
    if (s->valid) convexity += s->convexity / double(sides.size());
  }
  return {{"repose_angle", angle_deg},
          {"bed_height", bed_height},
          {"heap_height", profile.height},
          {"runout", runout},
          {"profile_convexity", convexity}};
}

std::map<std::string, double> heap_measures(const ReposeResult& heap, const std::string& heap_side) {
  return heap_measures(heap.angle_deg, heap.bed_height, heap.profile, heap_side);
}

}  // namespace repose
