#include "util/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "util/file_output.h"

namespace repose {

namespace fs = std::filesystem;

std::string temporary_path(const std::string& path) { return path + ".tmp." + std::to_string(::getpid()); }

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool) {
  std::string tmp = temporary_path(path);
  try {
    FileOutput out(tmp, FileOutput::Mode::Truncate, path);
    write(out.stream());
    out.close();
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw WriteError("cannot write " + path + ": " + ec.message());
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
}

void write_file_atomically(const std::string& path, const std::string& content) {
  write_file_atomically(path, [&](std::ostream& out) { out << content; }, true);
}

void write_status_file(const std::string& path, const std::string& content) {
  try {
    write_file_atomically(path, content);
  } catch (const WriteError&) {
    FileOutput out(path, FileOutput::Mode::Truncate);
    out.stream() << content;
    out.close();
  }
}

int remove_leftover_temporaries(const std::string& dir) {
  std::error_code ec;
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::string name = entry.path().filename().string();
    size_t at = name.rfind(".tmp.");
    if (at == std::string::npos || at + 5 == name.size() ||
        name.find_first_not_of("0123456789", at + 5) != std::string::npos || !entry.is_regular_file(ec))
      continue;
    removed += fs::remove(entry.path(), ec) ? 1 : 0;
  }
  return removed;
}

}  // namespace repose
