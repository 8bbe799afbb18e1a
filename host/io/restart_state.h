// The state a run continues from (`repose run --restart FILE`), read and checked before anything
// is written: a file that is not one, changed or damaged since it was written, inconsistent, of
// another version or of another case is refused with one line naming the file and what is wrong.
#pragma once
#include <string>

#include "engine/model.h"
#include "io/state_file.h"

namespace repose {

struct RestartPoint {
  HostState state;
  StateFileInfo info;
};

// Reads `path` for `model`, the case whose hash (io/provenance.h) is `case_hash`. Throws
// InputError (bad input: exit code 2).
RestartPoint read_restart_state(const std::string& path, const Model& model, const std::string& case_hash);

}  // namespace repose
