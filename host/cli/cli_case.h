// Loading a case for a verb: --set overrides applied, and a CaseError printed as the one-line
// `FILE:LINE: KEY: problem` message with exit code 2 (nothing is written before that); the
// case's warnings (unusual values, case/physical_ranges.h) are printed on stderr.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "case/case_loader.h"

namespace repose::cli {

// nullopt after printing the error; `extra` overrides come after the user's --set ones.
std::optional<CaseSpec> load_case_or_report(const std::string& path, const std::vector<std::string>& sets,
                                            const std::vector<CaseOverride>& extra = {});

}  // namespace repose::cli
