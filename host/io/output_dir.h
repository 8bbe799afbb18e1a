// An output folder belongs to one run: results of an older run never mix with a new one's
// (ParaView would load a frame series of both). Checked before the first step, so a run does not
// end with nowhere to write its results.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace repose {

// A folder or file a run cannot use; the message says which and why (exit code 2 in verbs).
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Makes `dir` ready for a new run: created when absent; an existing folder with anything in it is
// refused unless `overwrite`, which empties it first. Never empties a folder that holds one of
// `protect` (the case file, a restart state) or the working directory. Throws OutputError.
void prepare_output_dir(const std::string& dir, bool overwrite, const std::vector<std::string>& protect = {});

// Throws OutputError naming `path` when a file cannot be created there (a missing or read-only
// folder, a folder in the way): tried by creating and removing a probe file beside it.
void check_file_writable(const std::string& path, const std::string& what);

// `inner` is `dir` or lies inside it (after resolving both).
bool path_is_within(const std::string& inner, const std::string& dir);

}  // namespace repose
