#include "experiments/experiment.h"

#include <cstdarg>
#include <cstdio>
#include <stdexcept>

#include "util/atomic_file.h"

namespace repose {

Interaction& Experiment::tested_contact(CaseSpec& spec) const {
  throw std::runtime_error(spec.path + ": the " + id() + " experiment names no contact it calibrates");
}

DiagnosticOutcome Experiment::simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>&, bool) const {
  throw std::runtime_error(spec.path + ": diagnose does not simulate the " + id() + " experiment");
}

OutputFile text_file(std::string name, std::function<void(std::ostream&)> write) {
  return {std::move(name), [write = std::move(write)](const std::string& path) { write_file_atomically(path, write); }};
}

const ExperimentOutcome& measured_or_throw(const ExperimentOutcome& outcome) {
  if (outcome.status != OutcomeStatus::Measured) throw std::runtime_error(outcome.problem);
  return outcome;
}

OrderedJson with_status(const ExperimentOutcome& outcome) {
  OrderedJson j;
  bool measured = outcome.status == OutcomeStatus::Measured;
  j["status"] = measured ? "measured" : "failed";
  if (!measured) j["reason"] = outcome.problem;
  for (const auto& [key, value] : outcome.json.items())
    if (key != "status" && key != "reason") j[key] = value;
  return j;
}

std::vector<std::string> write_outcome(const ExperimentOutcome& outcome, const std::string& json_name,
                                       const std::string& dir) {
  // The result last: a failed series leaves no complete-looking JSON beside it.
  for (const OutputFile& f : outcome.files) f.write(dir + "/" + f.name);
  write_file_atomically(dir + "/" + json_name, [&](std::ostream& o) { o << outcome.json.dump(2) << "\n"; });
  std::vector<std::string> lines = outcome.lines;
  std::string wrote = "wrote " + dir + "/" + json_name;
  for (const OutputFile& f : outcome.files) wrote += ", " + f.name;
  lines.push_back(wrote);
  return lines;
}

std::string printf_text(const char* format, ...) {
  char buf[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

}  // namespace repose
