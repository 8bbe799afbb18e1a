#include "cli/verbs.h"

namespace repose::cli {

std::vector<Verb> engine_verbs() { return {}; }

}  // namespace repose::cli
