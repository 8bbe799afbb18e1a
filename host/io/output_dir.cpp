#include "io/output_dir.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

namespace repose {

namespace fs = std::filesystem;

bool path_is_within(const std::string& inner, const std::string& dir) {
  std::error_code ec;
  fs::path a = fs::weakly_canonical(fs::absolute(inner), ec), b = fs::weakly_canonical(fs::absolute(dir), ec);
  auto mismatch = std::mismatch(b.begin(), b.end(), a.begin(), a.end());
  return mismatch.first == b.end();
}

void prepare_output_dir(const std::string& dir, bool overwrite, const std::vector<std::string>& protect) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw OutputError("--out " + dir + " is a file, not a folder");
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec)) {
    if (!overwrite)
      throw OutputError("--out " + dir + " is not empty: an older run's files would mix with this one's. "
                        "Choose another --out, or pass --overwrite to delete what it holds first");
    if (path_is_within(fs::current_path().string(), dir))
      throw OutputError("--overwrite would delete " + dir + ", which holds the working directory");
    for (const auto& keep : protect)
      if (!keep.empty() && path_is_within(keep, dir))
        throw OutputError("--overwrite would delete " + keep + ", which this run reads: choose another --out");
    for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
  }
  fs::create_directories(dir, ec);
  if (ec) throw OutputError("cannot create the output folder " + dir + ": " + ec.message());
  check_file_writable((fs::path(dir) / "summary.json").string(), "--out");
}

void check_file_writable(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw OutputError(what + " " + path + " is a folder");
  fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) parent = ".";
  if (!fs::is_directory(parent, ec)) throw OutputError(what + " " + path + ": the folder " + parent.string() + " does not exist");
  std::string probe = (parent / (".repose-probe-" + std::to_string(::getpid()))).string();
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError(what + " " + path + " cannot be written: " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace repose
