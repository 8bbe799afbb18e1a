#include "util/version.h"

#include "repose_version.h"

namespace repose {

std::string repose_version() { return REPOSE_VERSION; }

}  // namespace repose
