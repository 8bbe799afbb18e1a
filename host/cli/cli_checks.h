// Validators for command-line values, so that no value is silently ignored or taken past its
// sense: CLI11 reports a failed check as "--option: message" and a non-zero exit, never a hang.
#pragma once
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "util/input_error.h"

namespace repose::cli {

// Exit codes (README, "Exit codes"): 0 done; 1 a failure while working (a full disk, no device,
// a reading the rig could not take); 2 bad input (a case, a data file, a command line, an output
// folder, a state file); 3 a calibration that missed its target; 128 + N stopped by signal N.
inline int failure_exit_code(const std::exception& e) { return dynamic_cast<const BadInput*>(&e) ? 2 : 1; }

// CLI11's exit codes (105, 106, 109, ...) for command-line errors become 2; --help stays 0.
inline int parse_exit_code(CLI::App& app, const CLI::ParseError& e) { return app.exit(e) == 0 ? 0 : 2; }

// CLI11_PARSE with the exit codes above.
#define REPOSE_PARSE(app, argc, argv)                  \
  try {                                                \
    (app).parse((argc), (argv));                       \
  } catch (const CLI::ParseError& parse_error) {       \
    return repose::cli::parse_exit_code(app, parse_error); \
  }

// A path that is given must name something: `--out ''` would silently mean the default.
inline CLI::Validator non_empty_path() {
  return CLI::Validator([](std::string& text) -> std::string { return text.empty() ? "an empty path names nothing" : ""; },
                        "PATH");
}

// A finite number > 0 (refuses nan, inf and negative values that CLI11's own ranges let through).
inline CLI::Validator finite_positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v)) return "'" + text + "' is not a number";
        if (!std::isfinite(v) || !(v > 0)) return "'" + text + "' must be a finite number greater than 0";
        return {};
      },
      "POSITIVE");
}

// A finite number in [low, high] (nan and inf refused).
inline CLI::Validator finite_between(double low, double high) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v)) return "'" + text + "' is not a number";
        if (!std::isfinite(v) || v < low || v > high) {
          char range[64];
          std::snprintf(range, sizeof range, "from %g to %g", low, high);
          return "'" + text + "' must be a finite number " + range;
        }
        return {};
      },
      "NUMBER");
}

// A finite number (nan and inf refused).
inline CLI::Validator finite_number() { return finite_between(-1e300, 1e300); }

// A whole number from `low` to `high`, with a message that says why the bound is there.
inline CLI::Validator whole_number(long long low, long long high, const std::string& why = "") {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        long long v = 0;
        if (!CLI::detail::lexical_cast(text, v)) return "'" + text + "' is not a whole number";
        if (v < low || v > high)
          return "'" + text + "' must be from " + std::to_string(low) + " to " + std::to_string(high) +
                 (why.empty() ? "" : " (" + why + ")");
        return {};
      },
      "INT in [" + std::to_string(low) + " - " + std::to_string(high) + "]");
}

// Threads of the cpu backend: more than a few per core only costs (and 100000 would hang).
inline CLI::Validator thread_count() { return whole_number(1, 1024, "threads of the cpu backend"); }

// A command line that parsed but does not make sense: the message on stderr, exit code 2.
inline int usage_error(const std::string& message) {
  std::fprintf(stderr, "error: %s\n", message.c_str());
  return 2;
}

}  // namespace repose::cli
