// Runs the built `repose` binary as a user would and captures what it prints (stdout and stderr
// together) and its exit status; scratch folders and file contents for checking what it wrote.
// Shared by the test folders that exercise verbs end to end.
#pragma once
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace repose::test {

struct CliRun {
  int status;          // exit code, -1 when killed by a signal
  std::string output;  // stdout and stderr
};

// `environment`: assignments put before the command ("NAME=value "), or empty.
inline CliRun run_repose_env(const std::string& environment, const std::string& arguments, const std::string& cwd = "") {
  const std::string command = (cwd.empty() ? "" : "cd '" + cwd + "' && ") + environment + std::string(REPOSE_BINARY) +
                              " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed for: " + command};
  std::string output;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

inline CliRun run_repose(const std::string& arguments, const std::string& cwd = "") {
  return run_repose_env("", arguments, cwd);
}

// Starts `repose ARGS...` in the background (stdout and stderr to `log`), for tests that signal
// it; returns its process id (waitpid it).
inline pid_t spawn_repose(const std::vector<std::string>& args, const std::string& log) {
  pid_t pid = fork();
  if (pid != 0) return pid;
  int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  dup2(fd, 1);
  dup2(fd, 2);
  std::vector<char*> argv{const_cast<char*>(REPOSE_BINARY)};
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execv(REPOSE_BINARY, argv.data());
  _exit(127);
}

// An empty scratch folder of this process (ctest runs test cases of one file at the same time).
inline std::filesystem::path fresh_dir(const std::string& name) {
  namespace fs = std::filesystem;
  fs::path d = fs::temp_directory_path() / ("repose_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A file's bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

}  // namespace repose::test
