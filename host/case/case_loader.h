// Reading a case file (TOML, SI units; docs/case-format.md) into a checked CaseSpec. The loader
// reads only: it never writes a file or prints. Every problem is a CaseError whose message is
// "FILE:LINE: KEY: what is wrong".
#pragma once
#include <string>
#include <vector>

#include "case/case_error.h"
#include "case/case_spec.h"

namespace repose {

// "set KEY to VALUE" before the case is checked; the key scheme is in case/case_override.h.
struct CaseOverride {
  std::string key;    // "simulation.end_time", "material.cabbage.density", "wall.0.material"
  std::string value;  // TOML value text: "0.5", "[0, 0, -9.8]", "clip"
};

// "KEY=VALUE" (as `--set` takes it) -> CaseOverride. Throws CaseError without '=' or key.
CaseOverride parse_override(const std::string& text);

// Reads, overrides, checks and expands a case: CaseSpec::spheres holds the explicit spheres
// followed by the spheres of every [[lattice]] and [[fill]]. Throws CaseError.
CaseSpec load_case(const std::string& path, const std::vector<CaseOverride>& overrides = {});

// Hash of CaseSpec::identity (16 hex digits): the same case parsed from differently commented
// or laid-out text gives the same hash; an edited value, override or input file changes it.
std::string case_hash(const CaseSpec& spec);

// The same from text in memory; virtual_path names the file in messages and in CaseSpec::path.
CaseSpec load_case_from_string(const std::string& toml_text, const std::string& virtual_path,
                               const std::vector<CaseOverride>& overrides = {});

}  // namespace repose
