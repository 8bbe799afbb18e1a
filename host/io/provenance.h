// What produced a result, recorded in every JSON result so it can be traced and reproduced:
// the program's version, the case (path and hash of what was parsed, host/case/case_loader.h),
// the --set overrides, the seed, the backend and the device it ran on.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "case/case_spec.h"

namespace repose {

struct Provenance {
  std::string case_path;
  std::string case_hash;
  std::vector<std::string> overrides;  // "KEY=VALUE", in the order applied
  uint64_t seed = 0;
  std::string backend;  // "cpu" or "vulkan"
  std::string device;   // the backend's own description (threads, or the Vulkan device and driver)
};

// The case's path, hash and seed; the rest is filled in by the caller.
Provenance provenance_of(const CaseSpec& spec, const std::vector<std::string>& overrides);
nlohmann::ordered_json provenance_json(const Provenance& p);
// {"version": ...} alone.
nlohmann::ordered_json version_json();
// For results computed from files rather than a simulated case (a fit from a table, a heap angle
// from a sphere CSV, a diagnosis from measured data): the version and each input file with the
// FNV-1a hash of its bytes.
nlohmann::ordered_json input_provenance(const std::vector<std::string>& files);
// The FNV-1a hash (16 hex digits) of a file's bytes.
std::string file_fnv1a(const std::string& path);

}  // namespace repose
