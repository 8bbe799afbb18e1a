// The progress line tracks what ends a run: a revised expected end, an end it cannot tell yet, a
// run past its expectation (never "step 211788/211740"), and the trends that estimate when a body
// stops (speed falling linearly) or a heap settles (energy falling exponentially).
#include <catch2/catch.hpp>

#include <cmath>

#include "util/progress.h"

using namespace repose;

TEST_CASE("the progress line counts to the expected end and never past it", "[util][progress]") {
  Progress p("roll", 211740, 1e-4, false);
  // Past the limit (the run's max_time): the total is where it is now, the ETA 0.
  std::string past = p.line(211788, 104, "");
  INFO(past);
  CHECK(past.find("step 211788/211788") != std::string::npos);
  CHECK(past.find("ETA 0.0 s") != std::string::npos);
  CHECK(past.find("years") == std::string::npos);
  // A revised expectation: the body stops at 2 s.
  p.expect_end_time(2.0, "(until the body stops)");
  std::string revised = p.line(10000, 10, "x 0.1 m");
  INFO(revised);
  CHECK(revised.find("t = 1 s of 2 s (until the body stops), step 10000/20000") != std::string::npos);
  CHECK(revised.find("1000 steps/s, ETA 10.0 s, x 0.1 m") != std::string::npos);
  // Not yet known: said, with the limit.
  p.expect_unknown_end("(the body has not started rolling)");
  std::string unknown = p.line(10000, 10, "");
  INFO(unknown);
  CHECK(unknown.find("(at most 21.17 s)") != std::string::npos);
  CHECK(unknown.find("ETA unknown (the body has not started rolling)") != std::string::npos);
}

TEST_CASE("falling trends estimate when a body stops and when a heap settles", "[util][progress]") {
  FallingTrend speed(0.5, false), energy(1.0, true);
  for (int k = 0; k <= 100; ++k) {
    double t = 0.01 * k;
    speed.add(t, 1 - 0.5 * t);      // a constant torque: speed falls linearly
    energy.add(t, std::exp(-2 * t));  // damping: energy falls exponentially
  }
  CHECK(speed.reaches(0.1) == Approx(1.8).epsilon(1e-9));
  CHECK(energy.reaches(1e-3) == Approx(std::log(1000.0) / 2).epsilon(1e-9));
  FallingTrend rising(1.0, false);
  for (int k = 0; k < 10; ++k) rising.add(k, k);
  CHECK(rising.reaches(0) < 0);  // not falling: no estimate
  CHECK(format_duration(-1) == "unknown");
  CHECK(format_duration(125) == "2m05s");
  CHECK(format_duration(1e12) == "more than 100 years");
}
