// An output folder belongs to one run: results of an older run never mix with a new one's
// (ParaView would load a frame series of both), and two processes never write it at once (their
// frames and CSV rows would interleave). Claimed before the first step, so a run does not end
// with nowhere to write its results.
#pragma once
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/file_lock.h"
#include "util/input_error.h"

namespace repose {

// A folder or file a run cannot use; the message says which and why (bad input: exit code 2).
struct OutputError : BadInput {
  using BadInput::BadInput;
};

// The lock file inside a claimed folder (removed when the claim ends; a stale one is ignored).
constexpr const char* kFolderLock = ".repose.lock";

// A folder claimed by this process for as long as the object lives.
class OutputFolder {
 public:
  // Creates `dir` when absent (with missing parents) and locks it (DIR/.repose.lock names this
  // process, its command line and start time). Throws OutputError when `dir` is a file, cannot be
  // created or written, or is held by another process (named in the message).
  explicit OutputFolder(std::string dir);
  // Releases the lock; removes the folders this claim created if they hold nothing (a run that
  // failed before writing anything leaves no empty folder behind).
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::string& dir() const { return dir_; }
  // Anything in it besides the lock.
  bool holds_files() const;
  // Readies it for a new run: a folder holding files is refused unless `overwrite`, which empties
  // it first; never when it holds one of `protect` (the case file, a restart state) or the
  // working directory. Throws OutputError.
  void make_ready(bool overwrite, const std::vector<std::string>& protect = {}) const;
  // Removes the temporaries (NAME.tmp.PID) a killed process left in it and in its `sub` folders.
  int remove_leftovers(const std::vector<std::string>& sub = {}) const;

 private:
  void remove_created() const;
  std::string dir_;
  std::vector<std::string> created_;  // deepest first
  std::unique_ptr<FileLock> lock_;
};

// Throws OutputError naming `path` when a file cannot be created there (a missing or read-only
// folder, a folder in the way): tried by creating and removing a probe file beside it.
void check_file_writable(const std::string& path, const std::string& what);

// `inner` is `dir` or lies inside it (after resolving both).
bool path_is_within(const std::string& inner, const std::string& dir);

}  // namespace repose
