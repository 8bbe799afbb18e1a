// When the particles are put in cell order again (host/engine/particle_order.h). A reorder
// downloads the state, sorts it on the host and uploads it: on the cpu backend a few hundredths
// of the steps between (the million-grain pour: ~2 %), but on a GPU, whose steps are a hundred
// times faster and whose state crosses the bus, it could cost more than the steps it speeds up.
// So a reorder is due every `every` list rebuilds, and (when capped) not before the batches
// since the last one have taken kStepsPerReorderCost times its wall time: a tenth of the run at
// most goes to reordering. The order never changes a run's bytes, so neither does this clock.
#pragma once
#include <cstdint>

namespace repose {

class ReorderSchedule {
 public:
  static constexpr double kStepsPerReorderCost = 9.0;

  // every: rebuilds between reorders (0: never); capped: also wait for the time above.
  ReorderSchedule(uint32_t every, bool capped) : every_(every), capped_(capped) {}

  bool due(uint64_t rebuilds) const {
    if (every_ == 0) return false;
    if (last_at_ < 0) return true;  // the first batch runs in cell order
    if (int64_t(rebuilds) < last_at_ + int64_t(every_)) return false;
    return !capped_ || stepped_seconds_ >= kStepsPerReorderCost * last_cost_;
  }
  // A reorder at this rebuild count took `seconds` of wall time (0: the start's, not timed).
  void reordered(uint64_t rebuilds, double seconds) {
    last_at_ = int64_t(rebuilds);
    last_cost_ = seconds;
    stepped_seconds_ = 0;
  }
  void stepped(double seconds) { stepped_seconds_ += seconds; }
  // After a restore: the next batch is put in order by the restored positions.
  void restart() { last_at_ = -1; }

 private:
  uint32_t every_;
  bool capped_;
  int64_t last_at_ = -1;       // rebuild count at the last reorder (-1: none yet)
  double last_cost_ = 0;       // its wall seconds
  double stepped_seconds_ = 0;  // wall seconds of the batches since
};

}  // namespace repose
