// Input files are read whole, so a device or pipe (/dev/zero) given by mistake would be read
// forever: every reader first asks what the path is.
#pragma once
#include <cstdint>
#include <string>

namespace repose {

// "" when `path` is a regular file of at most `largest` bytes (or does not exist: the reader
// then reports that itself); otherwise why it is no input file.
std::string why_not_input_file(const std::string& path, std::uintmax_t largest = std::uintmax_t(1) << 30);

}  // namespace repose
