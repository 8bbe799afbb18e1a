// An exclusive lock on a file (flock), held while the object lives, so that two processes never
// write one place at once (a campaign database, an output folder). The kernel drops the lock
// when the process ends, even by kill -9, so a killed run never leaves a folder locked. The file
// holds who has the lock (process, command line, start time), for the one refused.
#pragma once
#include <string>

#include "util/input_error.h"

namespace repose {

// Another process holds the lock; holder() is what it wrote ("process 123 (repose run ...),
// since 2026-01-02T03:04:05Z"). Bad input: choose another place, or wait (exit code 2).
class FileBusy : public BadInput {
 public:
  FileBusy(const std::string& message, std::string holder) : BadInput(message), holder_(std::move(holder)) {}
  const std::string& holder() const { return holder_; }

 private:
  std::string holder_;
};

class FileLock {
 public:
  // Takes the lock on `path` (created when absent), or throws FileBusy; throws
  // std::runtime_error when the file cannot be created.
  explicit FileLock(std::string path);
  // Releases the lock and removes the file.
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace repose
