#include "cli/verbs.h"

namespace repose::cli {

std::vector<Verb> geometry_verbs() { return {}; }

}  // namespace repose::cli
