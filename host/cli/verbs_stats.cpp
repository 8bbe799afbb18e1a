#include "cli/verbs.h"

namespace repose::cli {

std::vector<Verb> stats_verbs() { return {}; }

}  // namespace repose::cli
