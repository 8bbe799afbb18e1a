#include "io/provenance.h"

#include "case/case_loader.h"
#include "util/hash.h"
#include "util/version.h"

#include <fstream>
#include <sstream>

namespace repose {

Provenance provenance_of(const CaseSpec& spec, const std::vector<std::string>& overrides) {
  Provenance p;
  p.case_path = spec.path;
  p.case_hash = case_hash(spec);
  p.overrides = overrides;
  p.seed = spec.seed;
  return p;
}

nlohmann::ordered_json provenance_json(const Provenance& p) {
  nlohmann::ordered_json j = version_json();
  j["case"] = p.case_path;
  j["case_hash"] = p.case_hash;
  j["overrides"] = p.overrides;
  j["seed"] = p.seed;
  j["backend"] = p.backend;
  j["device"] = p.device;
  return j;
}

nlohmann::ordered_json input_provenance(const std::vector<std::string>& files) {
  nlohmann::ordered_json j = version_json();
  j["inputs"] = nlohmann::ordered_json::array();
  for (const auto& file : files) j["inputs"].push_back({{"file", file}, {"fnv1a", file_fnv1a(file)}});
  return j;
}

std::string file_fnv1a(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return fnv1a_hex(bytes.str());
}

nlohmann::ordered_json version_json() {
  nlohmann::ordered_json j;
  j["version"] = repose_version();
  return j;
}

}  // namespace repose
