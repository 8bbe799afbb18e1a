// Writes a file so that readers see either nothing or the whole of it: the content goes to a
// temporary file in the same folder (PATH.tmp.PID), which is renamed over the target once
// complete. Every write is checked (util/file_output.h): a failure names the file and the
// system's reason, and leaves the target as it was and no temporary behind.
#pragma once
#include <functional>
#include <ostream>
#include <string>

namespace repose {

// Calls write(stream) and commits; on any exception the temporary is removed and the target
// is untouched. Throws WriteError naming the path and the reason when it cannot write.
// (`binary` is kept for callers that say so: every file is written as bytes.)
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

// The same for content already in memory.
void write_file_atomically(const std::string& path, const std::string& content);

// For a status that must reach the disk when it is full (a run's "failed: No space left on
// device"): written atomically when it can be, else over the old file's own bytes.
void write_status_file(const std::string& path, const std::string& content);

// The temporary a write to `path` uses while it is not complete.
std::string temporary_path(const std::string& path);

// Removes the temporaries (NAME.tmp.PID) left in `dir` by a process that was killed while
// writing; call it only while holding the folder (io/output_dir.h). Returns how many.
int remove_leftover_temporaries(const std::string& dir);

}  // namespace repose
