#include "util/input_file.h"

#include <filesystem>

namespace repose {

std::string why_not_input_file(const std::string& path, std::uintmax_t largest) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return "";
  if (fs::is_directory(path, ec)) return "a folder, not a file";
  if (!fs::is_regular_file(path, ec)) return "a device or pipe, not a regular file";
  if (fs::file_size(path, ec) > largest)
    return "larger than " + std::to_string(largest >> 20) + " MiB: not the kind of file expected here";
  return "";
}

}  // namespace repose
