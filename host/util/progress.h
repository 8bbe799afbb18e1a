// Progress of a long run on stderr: simulated time, steps/s and ETA, at most once a second
// (rewritten in place on a terminal; otherwise a first line after 2 s, then one every 10 s, e.g.
// in CI logs). The ETA counts to the step the run is expected to end at. A run that ends on a
// condition (a body stops, a heap settles) revises that expectation as it learns
// (expect_end_time); while it cannot tell, the line says so instead of guessing, and a run past
// its expectation never prints a step count above its total.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace repose {

class Progress {
 public:
  // Steps count from 0; a restarted run begins at first_step (its rate counts from there).
  // total_steps: where the run ends, or at the latest (`limit`: its max_time) when it ends on a
  // condition: call expect_end_time() with the estimate, or expect_unknown_end().
  Progress(std::string label, uint64_t total_steps, double dt, bool enabled = true, uint64_t first_step = 0);
  void update(uint64_t steps_done, const std::string& extra = "");
  // The run is now expected to end at `seconds` of simulated time (clamped to the limit), for
  // `why` ("until the body stops"); a negative or non-finite estimate: unknown.
  void expect_end_time(double seconds, const std::string& why = "");
  void expect_unknown_end(const std::string& why = "");
  void set_label(std::string label) { label_ = std::move(label); }  // the phase, as it changes
  void finish();

  // The line update() prints (for tests): `elapsed` wall seconds since the start at `done` steps.
  std::string line(uint64_t done, double elapsed, const std::string& extra) const;

 private:
  std::string label_;
  uint64_t limit_;         // the total given: the run's end, or its latest end
  double expected_end_ = -1;  // steps; -1: the limit; -2: unknown
  std::string why_;
  double dt_;
  bool enabled_;
  bool tty_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point start_, last_;
  uint64_t first_ = 0;
};

// Progress through a known number of tasks (simulations) on stderr, one line per task as it
// starts: "LABEL k/N what, elapsed, ETA" (the ETA from the mean time of the tasks done).
class TaskProgress {
 public:
  TaskProgress(std::string label, int total, bool enabled);
  void next(const std::string& what);

 private:
  std::string label_;
  int total_, done_ = 0;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

// "12.3 s", "4m05s", "3h07m", "12d04h", "more than 100 years" (never a negative or wrapped number).
std::string format_duration(double seconds);

// When a quantity that falls steadily reaches `target`: a straight line through the last `window`
// seconds of samples (t, value) (a rolling body's speed: a constant torque slows it linearly),
// or through their logarithms (`logarithmic`: a settling heap's energy decays exponentially).
// Returns the time, or -1 when the samples do not fall (or are too few to tell).
class FallingTrend {
 public:
  FallingTrend(double window, bool logarithmic) : window_(window), log_(logarithmic) {}
  void add(double t, double value);
  double reaches(double target) const;
  void clear() { t_.clear(); v_.clear(); }

 private:
  double window_;
  bool log_;
  std::vector<double> t_, v_;
};

}  // namespace repose
