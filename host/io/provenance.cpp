#include "io/provenance.h"

#include "case/case_loader.h"
#include "util/version.h"

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

nlohmann::ordered_json version_json() {
  nlohmann::ordered_json j;
  j["version"] = repose_version();
  return j;
}

}  // namespace repose
