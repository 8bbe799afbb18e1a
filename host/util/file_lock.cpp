#include "util/file_lock.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace repose {

namespace {

// "process PID (COMMAND LINE), since TIME": what a refused process is told about this one.
std::string this_process() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string command((std::istreambuf_iterator<char>(in)), {});
  while (!command.empty() && command.back() == '\0') command.pop_back();
  for (char& c : command)
    if (c == '\0') c = ' ';
  if (command.size() > 300) command = command.substr(0, 300) + " ...";
  std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char since[32];
  std::strftime(since, sizeof since, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return "process " + std::to_string(::getpid()) + (command.empty() ? "" : " (" + command + ")") + ", since " + since;
}

std::string holder_of(int fd) {
  char text[512] = {0};
  ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string who = n > 0 ? std::string(text, size_t(n)) : "another process";
  while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
  return who;
}

// The descriptor still names the file at `path`: the lock's holder may have removed it (and
// released the lock) between our open and our flock, and the lock would then guard nothing.
bool still_at(int fd, const std::string& path) {
  struct stat a {}, b {};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

}  // namespace

FileLock::FileLock(std::string path) : path_(std::move(path)) {
  for (;;) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot create the lock file " + path_ + ": " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      std::string who = holder_of(fd_);
      ::close(fd_);
      throw FileBusy(path_ + " is locked by " + who, who);
    }
    if (still_at(fd_, path_)) break;
    ::close(fd_);
  }
  std::string me = this_process() + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) < 0) { /* the lock holds without the note */ }
}

FileLock::~FileLock() {
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace repose
