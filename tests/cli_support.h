// Runs the built `repose` binary as a user would and captures what it prints (stdout and stderr
// together) and its exit status. Shared by the test folders that exercise verbs end to end.
#pragma once
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace repose::test {

struct CliRun {
  int status;          // exit code, -1 when killed by a signal
  std::string output;  // stdout and stderr
};

inline CliRun run_repose(const std::string& arguments) {
  const std::string command = std::string(REPOSE_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed for: " + command};
  std::string output;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace repose::test
