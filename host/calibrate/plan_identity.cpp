// What identifies a plan's runs (plan.h): its canonical text, the text's hash, and the change
// between two canonical texts named key by key.
#include <algorithm>
#include <filesystem>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "calibrate/plan.h"
#include "util/hash.h"
#include "util/number_text.h"

namespace repose::calibrate {

namespace fs = std::filesystem;

namespace {

// The responses' keys: as before for one response on the campaign's case, indexed for several.
void response_lines(const CampaignPlan& p, std::map<std::string, std::string>& kv) {
  for (size_t i = 0; i < p.responses.size(); ++i) {
    const PlanResponse& r = p.responses[i];
    const std::string pre = p.responses.size() == 1 ? "response." : "response." + std::to_string(i) + ".";
    kv[pre + "name"] = r.name;
    kv[pre + "measured"] = exact_number(r.measured);
    kv[pre + "measured_sd"] = exact_number(r.measured_sd);
    kv[pre + "tolerance"] = exact_number(r.tolerance);
    if (r.measured_n != 1) kv[pre + "measured_n"] = std::to_string(r.measured_n);
    if (r.rig != 0) kv[pre + "rig"] = p.rigs[size_t(r.rig)].name;
    if (r.role == ResponseRole::verify) kv[pre + "role"] = "verify";
  }
}

void rig_lines(const CampaignPlan& p, std::map<std::string, std::string>& kv) {
  for (const auto& s : p.rigs[0].settings) kv["set." + s.key] = s.value;
  for (size_t i = 1; i < p.rigs.size(); ++i) {
    const PlanRig& r = p.rigs[i];
    const std::string pre = "rig." + r.name + ".";
    kv[pre + "experiment"] = r.experiment;
    kv[pre + "case"] = fs::path(r.case_path).filename().string();
    kv[pre + "case_hash"] = plan_hash(r.case_identity);
    kv[pre + "seed_key"] = r.seed_key;
    for (const auto& s : r.settings) kv[pre + "set." + s.key] = s.value;
  }
}

void design_lines(const DesignPlan& d, const CampaignPlan& p, std::map<std::string, std::string>& kv) {
  kv["design.type"] = d.type;
  kv["design.alpha"] = d.alpha;
  kv["design.centre"] = std::to_string(d.centre);
  kv["design.replicates"] = std::to_string(d.replicates);
  kv["design.model"] = d.model;
  kv["design.reduce"] = exact_number(d.reduce);
  std::string g;
  for (const auto& s : d.generators) g += (g.empty() ? "" : ",") + s;
  kv["design.generators"] = g;
  kv["design.levels"] = std::to_string(d.levels);
  kv["design.degree"] = std::to_string(d.degree);
  kv["design.order_seed"] = std::to_string(d.order_seed);
  std::string rows;
  for (const auto& row : d.table_rows) {
    rows += rows.empty() ? "" : ";";
    for (size_t j = 0; j < row.size(); ++j) rows.append(j ? "," : "").append(exact_number(row[j]));
  }
  kv["design.table_rows"] = rows;
  for (size_t j = 0; j < d.path_from.size(); ++j) {
    kv["design.from." + p.factors[j].name] = exact_number(d.path_from[j]);
    kv["design.to." + p.factors[j].name] = exact_number(d.path_to[j]);
  }
  for (auto [j, v] : d.fixed) kv["design.fix." + p.factors[size_t(j)].name] = exact_number(v);
}

}  // namespace

std::string canonical_plan_text(const CampaignPlan& p) {
  std::map<std::string, std::string> kv;
  const PlanRig& main = p.rigs[0];
  kv["campaign.experiment"] = main.experiment;
  kv["campaign.mode"] = p.mode == CampaignMode::design ? "design" : "adaptive";
  kv["campaign.backend"] = p.backend;
  kv["campaign.seed_key"] = main.seed_key;
  kv["campaign.base_seed"] = std::to_string(p.base_seed);
  kv["campaign.case"] = fs::path(main.case_path).filename().string();
  // What the base case parsed to and the files it reads, not its text: a comment does not
  // change the runs, an edited template or mesh does.
  kv["campaign.case_hash"] = plan_hash(main.case_identity);
  response_lines(p, kv);
  rig_lines(p, kv);
  for (size_t i = 0; i < p.factors.size(); ++i) {
    const auto& f = p.factors[i];
    std::string pre = "factor." + std::to_string(i) + ".";
    kv[pre + "name"] = f.name;
    kv[pre + "key"] = f.key;
    kv[pre + "low"] = exact_number(f.low);
    kv[pre + "high"] = exact_number(f.high);
  }
  if (p.mode == CampaignMode::design) {
    design_lines(p.design, p, kv);
  } else {
    // The budget is not here: raising it resumes the same campaign (the loop's proposals depend
    // only on the runs before them).
    kv["adaptive.initial"] = std::to_string(p.adaptive.initial);
    if (p.adaptive.seed_per_run) kv["adaptive.seeds"] = "per_run";  // absent: plans from before keep their hash
    if (p.adaptive.pilot > 0) {
      kv["adaptive.pilot"] = std::to_string(p.adaptive.pilot);
      kv["adaptive.pilot_points"] = std::to_string(p.adaptive.pilot_points);
    }
  }
  // The verification count is not here either unless other runs' seeds follow it: more
  // verification runs then resume the campaign (their seeds are base + 1, 2, ...).
  if (p.seeds_follow_verification()) kv["verification.runs"] = std::to_string(p.verification_runs);
  std::string text;
  for (const auto& [k, v] : kv) text += k + " = " + v + "\n";
  // The base case as parsed, line by line, so a change can be named (describe_plan_change).
  std::istringstream identity(main.case_identity);
  for (std::string line; std::getline(identity, line);)
    if (!line.empty()) text += kCaseLinePrefix + line + "\n";
  return text;
}

std::string canonical_plan_text_as_given(const CampaignPlan& plan) {
  CampaignPlan given = plan;
  for (PlanRig& rig : given.rigs) rig.case_identity = rig.case_identity_as_given;
  return canonical_plan_text(given);
}

std::string plan_hash(const std::string& text) { return fnv1a_hex(text); }

namespace {

struct CanonicalParts {
  std::map<std::string, std::string> settings;  // "key = value" lines
  std::multiset<std::string> case_lines;        // the base case as parsed
};

CanonicalParts split_canonical(const std::string& text) {
  CanonicalParts parts;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(kCaseLinePrefix, 0) == 0) {
      parts.case_lines.insert(line.substr(std::string(kCaseLinePrefix).size()));
      continue;
    }
    auto eq = line.find(" = ");
    if (eq != std::string::npos) parts.settings[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return parts;
}

// "base case: `a = 1` -> `a = 2`" from the lines only one side has (at most four shown).
std::string describe_case_change(const std::multiset<std::string>& a, const std::multiset<std::string>& b) {
  std::vector<std::string> gone, added;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(gone));
  std::set_difference(b.begin(), b.end(), a.begin(), a.end(), std::back_inserter(added));
  auto list = [](const std::vector<std::string>& lines) {
    std::string s;
    for (size_t k = 0; k < lines.size() && k < 4; ++k) s += (k ? ", `" : "`") + lines[k] + "`";
    if (lines.size() > 4) s += " and " + std::to_string(lines.size() - 4) + " more";
    return s.empty() ? std::string("(nothing)") : s;
  };
  return "base case (as parsed, files by content): " + list(gone) + " -> " + list(added);
}

}  // namespace

std::string describe_plan_change(const std::string& stored, const std::string& current) {
  auto a = split_canonical(stored), b = split_canonical(current);
  std::string out;
  auto add = [&](const std::string& s) { out += (out.empty() ? "" : "; ") + s; };
  bool case_lines = !a.case_lines.empty() && !b.case_lines.empty();
  for (const auto& [k, v] : a.settings) {
    if (case_lines && k == "campaign.case_hash") continue;  // named line by line below
    auto it = b.settings.find(k);
    if (it == b.settings.end()) add(k + ": " + v + " -> (removed)");
    else if (it->second != v) add(k + ": " + v + " -> " + it->second);
  }
  for (const auto& [k, v] : b.settings)
    if (!a.settings.count(k)) add(k + ": (new) " + v);
  if (case_lines && a.case_lines != b.case_lines) add(describe_case_change(a.case_lines, b.case_lines));
  return out.empty() ? "no difference" : out;
}

}  // namespace repose::calibrate
