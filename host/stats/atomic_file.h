// Whole-file writes that either happen completely or not at all: the text goes to a temporary
// file next to the target, is flushed, and is renamed over the target. A crash or an error never
// leaves a half-written design or fit file behind.
#pragma once
#include <string>

namespace repose::stats {

void write_file_atomic(const std::string& path, const std::string& content);

}  // namespace repose::stats
