#include "util/file_output.h"

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <streambuf>
#include <unistd.h>
#include <vector>

namespace repose {

namespace {

std::atomic<uint64_t> g_writes{0};

// The write count at which one write fails (0: none), from REPOSE_FAIL_WRITE at first use.
std::atomic<uint64_t>& failing_write() {
  static std::atomic<uint64_t> at{[] {
    const char* n = std::getenv("REPOSE_FAIL_WRITE");
    return n ? std::strtoull(n, nullptr, 10) : 0ull;
  }()};
  return at;
}

ssize_t system_write(int fd, const char* data, size_t bytes) {
  if (++g_writes == failing_write().load()) {
    errno = ENOSPC;
    return -1;
  }
  return ::write(fd, data, bytes);
}

}  // namespace

void fail_nth_write(uint64_t n) { failing_write() = n ? g_writes.load() + n : 0; }

// A stream buffer over a file descriptor that keeps the errno of its first failed write.
class FileOutput::Buffer : public std::streambuf {
 public:
  explicit Buffer(int fd) : fd_(fd), data_(1 << 16) { setp(data_.data(), data_.data() + data_.size()); }
  int fd() const { return fd_; }
  int error() const { return error_; }
  void set_error(int e) { if (!error_) error_ = e; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n > epptr() - pptr()) {
      if (!drain()) return 0;
      if (n >= std::streamsize(data_.size())) return put_all(s, size_t(n)) ? n : 0;
    }
    std::memcpy(pptr(), s, size_t(n));
    pbump(int(n));
    return n;
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    size_t n = size_t(pptr() - pbase());
    setp(data_.data(), data_.data() + data_.size());
    return put_all(data_.data(), n);
  }
  bool put_all(const char* p, size_t n) {
    if (error_) return false;
    while (n > 0) {
      ssize_t k = system_write(fd_, p, n);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0) {
        set_error(k < 0 ? errno : EIO);
        return false;
      }
      p += k;
      n -= size_t(k);
    }
    return true;
  }

  int fd_;
  std::vector<char> data_;
  int error_ = 0;
};

FileOutput::FileOutput(const std::string& path, Mode mode, const std::string& shown)
    : out_(nullptr), shown_(shown.empty() ? path : shown) {
  int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (mode == Mode::Append ? O_APPEND : O_TRUNC);
  int fd = ::open(path.c_str(), flags, 0644);
  if (fd < 0) fail(errno);
  buffer_ = std::make_unique<Buffer>(fd);
  out_.rdbuf(buffer_.get());
}

FileOutput::~FileOutput() {
  if (buffer_ && buffer_->fd() >= 0) ::close(buffer_->fd());
}

void FileOutput::fail(int error) const {
  throw WriteError("cannot write " + shown_ + ": " + std::strerror(error));
}

void FileOutput::flush() {
  out_.flush();
  if (buffer_->error()) fail(buffer_->error());
  if (!out_) fail(EIO);
}

void FileOutput::close() {
  flush();
  int fd = buffer_->fd();
  buffer_ = std::make_unique<Buffer>(-1);
  out_.rdbuf(buffer_.get());
  if (::close(fd) != 0) fail(errno);
}

}  // namespace repose
