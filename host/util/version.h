// The version of this build: `git describe --always --dirty --tags` of the source it was built
// from (cmake/git_version.cmake), e.g. "158eedc" or "v1.2-3-g158eedc-dirty".
#pragma once
#include <string>

namespace repose {

std::string repose_version();

}  // namespace repose
