#include "io/output_dir.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

#include "util/atomic_file.h"

namespace repose {

namespace fs = std::filesystem;

bool path_is_within(const std::string& inner, const std::string& dir) {
  std::error_code ec;
  fs::path a = fs::weakly_canonical(fs::absolute(inner), ec), b = fs::weakly_canonical(fs::absolute(dir), ec);
  auto mismatch = std::mismatch(b.begin(), b.end(), a.begin(), a.end());
  return mismatch.first == b.end();
}

OutputFolder::OutputFolder(std::string dir) : dir_(std::move(dir)) {
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec)) throw OutputError("--out " + dir_ + " is a file, not a folder");
  for (fs::path p = fs::absolute(dir_, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created_.push_back(p.string());
    if (p == p.parent_path()) break;
  }
  fs::create_directories(dir_, ec);
  if (ec) {
    remove_created();
    throw OutputError("cannot create the output folder " + dir_ + ": " + ec.message());
  }
  try {
    lock_ = std::make_unique<FileLock>((fs::path(dir_) / kFolderLock).string());
  } catch (const FileBusy& busy) {
    remove_created();
    throw OutputError("--out " + dir_ + " is in use by " + busy.holder() + ": wait for it to finish, or choose another --out");
  } catch (const std::exception& e) {
    remove_created();
    throw OutputError("--out " + dir_ + " cannot be written: " + e.what());
  }
}

OutputFolder::~OutputFolder() {
  lock_.reset();
  remove_created();
}

void OutputFolder::remove_created() const {
  std::error_code ec;
  for (const auto& d : created_)
    if (!fs::remove(d, ec)) break;  // not empty (or gone): its parents are not empty either
}

bool OutputFolder::holds_files() const {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir_, ec))
    if (entry.path().filename() != kFolderLock) return true;
  return false;
}

void OutputFolder::make_ready(bool overwrite, const std::vector<std::string>& protect) const {
  if (!holds_files()) return;
  if (!overwrite)
    throw OutputError("--out " + dir_ + " is not empty: an older run's files would mix with this one's. "
                      "Choose another --out, or pass --overwrite to delete what it holds first");
  if (path_is_within(fs::current_path().string(), dir_))
    throw OutputError("--overwrite would delete " + dir_ + ", which holds the working directory");
  for (const auto& keep : protect)
    if (!keep.empty() && path_is_within(keep, dir_))
      throw OutputError("--overwrite would delete " + keep + ", which this run reads: choose another --out");
  for (const auto& entry : fs::directory_iterator(dir_))
    if (entry.path().filename() != kFolderLock) fs::remove_all(entry.path());
}

int OutputFolder::remove_leftovers(const std::vector<std::string>& sub) const {
  int removed = remove_leftover_temporaries(dir_);
  for (const auto& s : sub) removed += remove_leftover_temporaries((fs::path(dir_) / s).string());
  return removed;
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
