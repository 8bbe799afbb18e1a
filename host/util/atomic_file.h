// Writes a file so that readers see either nothing or the whole of it: the content goes to a
// temporary file in the same folder, which is renamed over the target once complete.
#pragma once
#include <fstream>
#include <functional>
#include <string>

namespace repose {

// Calls write(stream) and commits; on any exception the temporary is removed and the target
// is untouched. Throws std::runtime_error naming the path when it cannot write.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

// The same for content already in memory.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace repose
