// Writing result files so that a failure is never silent: every write to the system is checked,
// and a failure names the file and the system's own reason ("No space left on device"). The one
// home of writing: atomic files (util/atomic_file.h) and streamed CSVs both go through it.
#pragma once
#include <cstdint>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

namespace repose {

// A write that failed, naming the file and the system's reason. Not bad input: exit code 1.
struct WriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A file opened for writing, as a buffered std::ostream. A failed write makes the stream bad and
// is kept; flush() and close() then throw WriteError with its reason.
class FileOutput {
 public:
  enum class Mode { Truncate, Append };
  // Opens `path`; messages name `shown` (default: path; the target of a temporary file).
  // Throws WriteError when it cannot be opened.
  FileOutput(const std::string& path, Mode mode, const std::string& shown = "");
  ~FileOutput();  // closes without reporting: call close() to learn whether everything was written
  FileOutput(const FileOutput&) = delete;
  FileOutput& operator=(const FileOutput&) = delete;

  std::ostream& stream() { return out_; }
  // Everything written so far reaches the system (a killed run keeps it), or WriteError.
  void flush();
  // flush(), then closes the file (whose close can report a failed write too), or WriteError.
  void close();

 private:
  class Buffer;
  [[noreturn]] void fail(int error) const;
  std::unique_ptr<Buffer> buffer_;
  std::ostream out_;
  std::string shown_;
};

// Fault injection, to test what a full disk does: the Nth write to the system from now fails
// once with ENOSPC, as a disk that fills and frees the space again when the partial file is
// removed (0: none). REPOSE_FAIL_WRITE=N in the environment does the same from the start.
void fail_nth_write(uint64_t n);

}  // namespace repose
