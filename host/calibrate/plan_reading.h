// The plan reader's shared parts (plan.h's load_plan): a table of the plan read with located
// errors, and the readers of the factors, the design and the adaptive loop (plan_design.cpp) that
// load_plan (plan.cpp) calls after the campaign, its rigs and responses. Internal to host/calibrate.
#pragma once
#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <vector>

#include "calibrate/plan.h"
#include "case/toml_section.h"

namespace repose::calibrate {

// A table of the plan, read as the case loader reads a case's (located errors, unknown keys with
// the nearest allowed one), with the plan's own rules.
class PlanTable : public Section {
 public:
  PlanTable(const toml::table& table, const std::string& file, std::string prefix)
      : Section(table, std::move(prefix), file) {}

  void allow_only(const std::vector<std::string>& allowed) const {
    Section::allow_only(allowed, prefix().empty() ? std::string("the plan") : "[" + prefix() + "]");
  }
  std::string required_text(std::string_view k) const {
    std::string v = Section::required_text(k);
    if (v.empty()) fail(k, "must not be empty");
    return v;
  }
  int integer_at_least(std::string_view k, int fallback, int least) const {
    auto v = integer(k);
    if (!v) return fallback;
    if (*v < least) fail(k, "must be at least " + std::to_string(least));
    if (*v > 100000) fail(k, "is unreasonably large");
    return int(*v);
  }
};

// A rig's or factor's name: letters, digits and _, starting with a letter or _.
bool valid_name(const std::string& n);

// [[factor]]: the case keys the campaign varies, each with its range.
void read_factors(const toml::node& node, const std::string& file, CampaignPlan& plan);
// [design] of a design campaign, checked against the factors (estimable model, enough points).
void read_design(const PlanTable& t, CampaignPlan& plan);
// [adaptive] of an adaptive campaign: its start, budget, seeds and noise pilot.
void read_adaptive(const PlanTable& t, CampaignPlan& plan);

}  // namespace repose::calibrate
