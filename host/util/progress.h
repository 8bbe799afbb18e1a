// Progress of a long run on stderr: simulated time, steps/s and ETA, at most once a second
// (rewritten in place on a terminal, one line every 10 s otherwise, e.g. in CI logs).
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace repose {

class Progress {
 public:
  Progress(std::string label, uint64_t total_steps, double dt, bool enabled = true);
  void update(uint64_t steps_done, const std::string& extra = "");
  void finish();

 private:
  std::string label_;
  uint64_t total_;
  double dt_;
  bool enabled_;
  bool tty_;
  std::chrono::steady_clock::time_point start_, last_;
  uint64_t last_steps_ = 0;
};

std::string format_duration(double seconds);

}  // namespace repose
