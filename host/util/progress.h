// Progress of a long run on stderr: simulated time, steps/s and ETA, at most once a second
// (rewritten in place on a terminal, one line every 10 s otherwise, e.g. in CI logs).
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace repose {

class Progress {
 public:
  // Steps count from 0; a restarted run begins at first_step (its rate counts from there).
  Progress(std::string label, uint64_t total_steps, double dt, bool enabled = true, uint64_t first_step = 0);
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
  uint64_t first_ = 0;
};

// "12.3 s", "4m05s", "3h07m", "12d04h", "more than 100 years" (never a negative or wrapped number).
std::string format_duration(double seconds);

}  // namespace repose
