// The candidate model extensions' rows (diagnosis/extensions.cpp) declare what a reader and the
// diagnosis need: measures that exist, usable search ranges, case keys and physics; and every row
// is listed by `repose extensions` and documented in docs/diagnosis.md's table.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "../cli_support.h"
#include "diagnosis/extensions.h"
#include "experiments/registry.h"

using namespace repose;

TEST_CASE("each extension row names known measures, usable ranges, its case keys and physics", "[diagnosis]") {
  std::vector<std::string> measures;
  for (const MeasureInfo& m : diagnosed_measures()) measures.push_back(m.name);
  for (const ModelExtension& e : model_extensions()) {
    INFO(e.id);
    CHECK(find_extension(e.id) == &e);
    CHECK_FALSE(e.description.empty());
    CHECK_FALSE(e.physics.empty());
    CHECK_FALSE(e.case_keys.empty());
    CHECK((e.apply || !e.pending_reason.empty()));
    CHECK((!e.revealed_by.empty() || !e.pending_reason.empty()));
    for (const std::string& m : e.revealed_by) {
      INFO(m);
      CHECK(std::find(measures.begin(), measures.end(), m) != measures.end());
    }
    REQUIRE_FALSE(e.parameters.empty());
    for (const FreeParameter& p : e.parameters) {
      INFO(p.name);
      CHECK(p.lo < p.hi);
      if (p.log_scale) CHECK(p.lo > 0);
    }
  }
}

TEST_CASE("repose extensions lists every row, and docs/diagnosis.md documents each", "[diagnosis][cli]") {
  const test::CliRun run = test::run_repose("extensions");
  REQUIRE(run.status == 0);
  std::ifstream in(std::string(REPOSE_SOURCE_DIR) + "/docs/diagnosis.md");
  std::stringstream docs;
  docs << in.rdbuf();
  for (const ModelExtension& e : model_extensions()) {
    INFO(e.id);
    CHECK(run.output.find(e.id + "\n") != std::string::npos);
    CHECK(run.output.find(e.case_keys) != std::string::npos);
    CHECK(docs.str().find("| `" + e.id + "` |") != std::string::npos);
  }
}
