#include "cli/cli_case.h"

#include <cstdio>

#include "case/case_error.h"

namespace repose::cli {

std::optional<CaseSpec> load_case_or_report(const std::string& path, const std::vector<std::string>& sets,
                                            const std::vector<CaseOverride>& extra) {
  try {
    std::vector<CaseOverride> overrides;
    for (const auto& s : sets) overrides.push_back(parse_override(s));
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    CaseSpec spec = load_case(path, overrides);
    for (const auto& warning : spec.warnings) std::fprintf(stderr, "%s\n", warning.c_str());
    return spec;
  } catch (const CaseError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return std::nullopt;
  }
}

}  // namespace repose::cli
