// Reading a calibration plan (plan.h): the [campaign], its [set], [[rig]]s and responses, then
// the factors, design or adaptive loop (plan_design.cpp), then every rig's case tried with the
// plan's settings; and the plan's small helpers (run overrides, coded and actual values).
#include "calibrate/plan.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "calibrate/experiment_runner.h"
#include "calibrate/plan_reading.h"
#include "util/input_file.h"
#include "util/number_text.h"
#include "util/path_name.h"

namespace repose::calibrate {

namespace fs = std::filesystem;

bool valid_name(const std::string& n) {
  if (n.empty() || !(std::isalpha((unsigned char)n[0]) || n[0] == '_')) return false;
  for (char c : n)
    if (!(std::isalnum((unsigned char)c) || c == '_')) return false;
  return true;
}

namespace {

// A TOML value as override text: strings bare, everything else as TOML writes it.
std::string value_text(const toml::node& node) {
  if (auto s = node.value<std::string>(); s && node.is_string()) return *s;
  if (node.is_floating_point()) return exact_number(*node.value<double>());
  std::ostringstream out;
  node.visit([&](auto&& v) { out << v; });
  return out.str();
}

std::string read_text(const std::string& path) {
  if (!why_not_input_file(path, 16u << 20).empty()) return {};
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A case file named by `key` in table t, resolved against the plan's folder, with its text.
void read_case_file(const PlanTable& t, const std::string& key, const CampaignPlan& plan, PlanRig& rig) {
  std::string rel = t.required_text(key);
  fs::path case_path = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(plan.path).parent_path() / rel;
  rig.case_path = case_path.lexically_normal().string();
  if (!fs::is_regular_file(case_path)) t.fail(key, "no case file " + rig.case_path);
  rig.case_text = read_text(rig.case_path);
}

void read_experiment(const PlanTable& t, PlanRig& rig, const std::string& fallback) {
  rig.experiment = fallback.empty() ? t.required_text("experiment") : t.text("experiment").value_or(fallback);
  try {
    find_experiment(rig.experiment);
  } catch (const std::exception& e) {
    t.fail("experiment", e.what());
  }
}

void read_campaign(const PlanTable& t, CampaignPlan& plan) {
  t.allow_only({"name", "experiment", "case", "mode", "backend", "seed_key", "base_seed"});
  PlanRig rig;
  rig.where = t.where("case");
  read_experiment(t, rig, "");
  read_case_file(t, "case", plan, rig);
  rig.seed_key = t.text("seed_key").value_or("simulation.seed");
  plan.rigs.push_back(rig);
  plan.name = t.text("name").value_or(fs::path(plan.path).stem().string());
  if (std::string why = why_not_path_name(plan.name); !why.empty() && t.has("name")) t.fail("name", why);  // out/calibrate/NAME
  if (auto mode = t.text("mode")) {
    if (*mode == "design") plan.mode = CampaignMode::design;
    else if (*mode == "adaptive") plan.mode = CampaignMode::adaptive;
    else t.fail("mode", "expected \"design\" or \"adaptive\", got \"" + *mode + "\"");
  }
  plan.backend = t.text("backend").value_or(kLibraryBackend);
  if (plan.backend != "cpu" && plan.backend != "vulkan") t.fail("backend", "expected \"cpu\" or \"vulkan\"");
  if (auto s = t.integer("base_seed")) {
    if (*s < 0) t.fail("base_seed", "must not be negative");
    plan.base_seed = uint64_t(*s);
  }
}

// [set] or a rig's set: case keys applied to every run of the rig, before the factors.
std::vector<PlanSetting> read_settings(const toml::table& table, const std::string& file, const std::string& prefix) {
  std::vector<PlanSetting> out;
  for (auto&& [k, node] : table)
    out.push_back({std::string(k.str()), value_text(node), {file, prefix + "." + std::string(k.str()), int(k.source().begin.line)}});
  return out;
}

// [[rig]]: another case the campaign runs (a response names it by `rig`).
void read_rigs(const toml::node& node, const std::string& file, CampaignPlan& plan) {
  const toml::array* list = node.as_array();
  if (!list || !list->is_array_of_tables())
    throw CaseError({file, "rig", int(node.source().begin.line)}, "expected [[rig]] tables");
  for (size_t i = 0; i < list->size(); ++i) {
    const toml::table& rt = *list->get(i)->as_table();
    PlanTable t(rt, file, "rig." + std::to_string(i));
    t.allow_only({"name", "experiment", "case", "seed_key", "set"});
    PlanRig rig;
    rig.name = t.required_text("name");
    if (!valid_name(rig.name)) t.fail("name", "'" + rig.name + "': use letters, digits and _, starting with a letter");
    for (const auto& other : plan.rigs)
      if (other.name == rig.name) t.fail("name", "a rig named '" + rig.name + "' is listed twice");
    rig.where = t.where("case");
    read_experiment(t, rig, plan.rigs[0].experiment);
    read_case_file(t, "case", plan, rig);
    rig.seed_key = t.text("seed_key").value_or("simulation.seed");
    if (const toml::node* set = rt.get("set")) {
      if (!set->is_table()) t.fail("set", "expected a table of case keys, e.g. set = { \"experiment.views\" = 16 }");
      rig.settings = read_settings(*set->as_table(), file, "rig." + rig.name + ".set");
    }
    plan.rigs.push_back(rig);
  }
}

// One [response] table (or one of [[response]]): a response of its rig's experiment and the
// lab's value.
PlanResponse read_response(const PlanTable& t, const CampaignPlan& plan) {
  t.allow_only({"name", "measured", "measured_sd", "measured_n", "tolerance", "rig", "role", "noise_sd"});
  PlanResponse r;
  r.where = t.where("name");
  r.name = t.required_text("name");
  if (auto rig = t.text("rig")) {
    r.rig = -1;
    for (size_t i = 0; i < plan.rigs.size(); ++i)
      if (plan.rigs[i].name == *rig) r.rig = int(i);
    if (r.rig < 0) t.fail("rig", "no [[rig]] named '" + *rig + "'");
  }
  const std::string& experiment = plan.rigs[size_t(r.rig)].experiment;
  const auto& names = find_experiment(experiment).responses;
  if (std::find(names.begin(), names.end(), r.name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    t.fail("name", "experiment '" + experiment + "' has no response '" + r.name + "' (it gives " + list + ")");
  }
  r.label = r.rig == 0 ? r.name : r.name + "@" + plan.rigs[size_t(r.rig)].name;
  r.measured = t.required_number("measured");
  r.measured_sd = t.number("measured_sd").value_or(0.0);
  if (r.measured_sd < 0) t.fail("measured_sd", "must not be negative");
  r.measured_n = t.integer_at_least("measured_n", 1, 1);
  r.noise_sd = t.number("noise_sd").value_or(0.0);
  if (r.noise_sd < 0) t.fail("noise_sd", "must not be negative");
  r.tolerance = t.number("tolerance").value_or(0.01);
  if (!(r.tolerance > 0 && r.tolerance < 1)) t.fail("tolerance", "must be a fraction in (0, 1), e.g. 0.01 for 1 %");
  if (r.measured == 0) t.fail("measured", "must not be zero (the tolerance is relative to it)");
  if (auto role = t.text("role")) {
    if (*role == "verify") r.role = ResponseRole::verify;
    else if (*role != "calibrate") t.fail("role", "expected \"calibrate\" (fitted and verified) or \"verify\" (only checked)");
  }
  return r;
}

// [response] (one) or [[response]] (several); labels must differ and one must calibrate.
void read_responses(const toml::node& node, const std::string& file, CampaignPlan& plan) {
  if (const toml::table* one = node.as_table()) {
    plan.responses.push_back(read_response(PlanTable(*one, file, "response"), plan));
  } else if (const toml::array* list = node.as_array(); list && list->is_array_of_tables()) {
    for (size_t i = 0; i < list->size(); ++i)
      plan.responses.push_back(read_response(PlanTable(*list->get(i)->as_table(), file, "response." + std::to_string(i)), plan));
  } else {
    throw CaseError({file, "response", int(node.source().begin.line)}, "expected a [response] table or [[response]] tables");
  }
  std::set<std::string> labels;
  for (const auto& r : plan.responses)
    if (!labels.insert(r.label).second)
      throw CaseError(r.where, "response '" + r.label + "' is listed twice (give each rig its own with rig = \"NAME\")");
  if (plan.calibration_responses().empty())
    throw CaseError({file, "response", int(node.source().begin.line)}, "every response has role = \"verify\": one must calibrate");
}

// Tries each rig's settings and every factor's extremes on its case, so an unknown key or a value
// the case refuses is reported at the plan line that asks for it, before anything runs.
void check_against_case(CampaignPlan& plan, PlanRig& rig, const SourceRef& set_where) {
  std::vector<CaseOverride> base;
  for (const auto& s : rig.settings) base.push_back({s.key, s.value});
  const std::string what = rig.name.empty() ? "the base case" : "rig '" + rig.name + "''s case";
  CaseSpec spec;
  try {
    spec = load_case_from_string(rig.case_text, rig.case_path, base);
  } catch (const CaseError& e) {
    throw CaseError(rig.settings.empty() ? set_where : rig.settings.front().where,
                    what + " refuses the settings: " + e.what());
  }
  rig.case_identity_as_given = spec.identity;
  if (!spec.experiment.type.empty() && spec.experiment.type != rig.experiment)
    throw CaseError(rig.name.empty() ? SourceRef{plan.path, "campaign.experiment", 0} : rig.where,
                    what + " " + rig.case_path + " is a '" + spec.experiment.type + "' experiment, not '" + rig.experiment + "'");
  for (const auto& f : plan.factors)
    for (double v : {f.low, f.high}) {
      std::vector<CaseOverride> o = base;
      o.push_back({f.key, exact_number(v)});
      try {
        load_case_from_string(rig.case_text, rig.case_path, o);
      } catch (const CaseError& e) {
        throw CaseError(f.where, "not a key " + what + " accepts at " + format_number(v) + ": " + e.what());
      }
    }
  std::vector<CaseOverride> pinned = base;
  for (const auto& f : plan.factors) pinned.push_back({f.key, exact_number(f.low)});
  rig.case_identity = load_case_from_string(rig.case_text, rig.case_path, pinned).identity;
}

// The campaign's base seed when the plan gives none: the base case's simulation.seed.
void default_base_seed(CampaignPlan& plan, const toml::table& root, const SourceRef& set_where) {
  const PlanRig& rig = plan.rigs[0];
  if (rig.seed_key != "simulation.seed" || root["campaign"]["base_seed"]) return;
  std::vector<CaseOverride> base;
  for (const auto& st : rig.settings) base.push_back({st.key, st.value});
  try {
    plan.base_seed = load_case_from_string(rig.case_text, rig.case_path, base).seed;
  } catch (const CaseError& e) {
    throw CaseError(set_where, std::string("the base case refuses the settings: ") + e.what());
  }
}

}  // namespace

double PlanResponse::absolute_tolerance() const { return tolerance * std::abs(measured); }
double PlanResponse::measured_se() const { return measured_sd / std::sqrt(double(measured_n)); }

std::vector<std::string> CampaignPlan::factor_names() const {
  std::vector<std::string> n;
  for (const auto& f : factors) n.push_back(f.name);
  return n;
}

std::vector<int> CampaignPlan::calibration_responses() const {
  std::vector<int> out;
  for (size_t i = 0; i < responses.size(); ++i)
    if (responses[i].role == ResponseRole::calibrate) out.push_back(int(i));
  return out;
}

std::vector<int> CampaignPlan::verified_responses() const {
  std::vector<int> out;
  for (size_t i = 0; i < responses.size(); ++i)
    if (responses[i].role == ResponseRole::verify) out.push_back(int(i));
  return out.empty() ? calibration_responses() : out;
}

std::vector<int> CampaignPlan::rigs_of(const std::vector<int>& list) const {
  std::set<int> rigs;
  for (int r : list) rigs.insert(responses[size_t(r)].rig);
  return {rigs.begin(), rigs.end()};
}

CampaignPlan load_plan(const std::string& path) {
  CampaignPlan plan;
  plan.path = path;
  if (!fs::exists(path)) throw CaseError({path, "", 0}, "no such plan file");
  if (auto why = why_not_input_file(path, 16u << 20); !why.empty()) throw CaseError({path, "", 0}, "not a plan file: " + why);
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw CaseError({path, "", int(e.source().begin.line)}, std::string(e.description()), int(e.source().begin.column));
  }
  PlanTable top(root, path, "");
  top.allow_only({"campaign", "response", "set", "rig", "factor", "design", "verification", "adaptive"});
  auto section = [&](const char* name, bool required) -> std::optional<PlanTable> {
    const toml::node* n = root.get(name);
    if (!n) {
      if (required) throw CaseError({path, name, 0}, std::string("missing [") + name + "] table");
      return std::nullopt;
    }
    if (!n->is_table()) top.fail(name, std::string("expected a table [") + name + "]");
    return PlanTable(*n->as_table(), path, name);
  };
  read_campaign(*section("campaign", true), plan);
  SourceRef set_where{path, "set", 0};
  if (auto set = section("set", false)) {
    plan.rigs[0].settings = read_settings(set->table(), path, "set");
    if (const toml::node* n = root.get("set")) set_where.line = int(n->source().begin.line);
  }
  if (const toml::node* rigs = root.get("rig")) read_rigs(*rigs, path, plan);
  if (const toml::node* r = root.get("response")) read_responses(*r, path, plan);
  else throw CaseError({path, "response", 0}, "missing [response] table (the measured value to match)");
  if (const toml::node* f = root.get("factor")) read_factors(*f, path, plan);
  else throw CaseError({path, "factor", 0}, "missing [[factor]] tables (the parameters to calibrate)");
  default_base_seed(plan, root, set_where);
  auto design = section("design", false);
  auto adaptive = section("adaptive", false);
  if (plan.mode == CampaignMode::design) {
    if (adaptive) adaptive->fail("an [adaptive] table needs campaign.mode = \"adaptive\"");
    read_design(design ? *design : PlanTable(toml::table{}, path, "design"), plan);
  } else {
    if (design) design->fail("a [design] table belongs to campaign.mode = \"design\"");
    static const toml::table empty;
    read_adaptive(adaptive ? *adaptive : PlanTable(empty, path, "adaptive"), plan);
  }
  if (auto v = section("verification", false)) {
    v->allow_only({"runs"});
    plan.verification_runs = v->integer_at_least("runs", 3, 0);
  }
  for (auto& rig : plan.rigs) check_against_case(plan, rig, set_where);
  return plan;
}

std::vector<CaseOverride> run_overrides(const CampaignPlan& plan, int rig, const std::vector<double>& x, std::uint64_t seed) {
  const PlanRig& r = plan.rigs[size_t(rig)];
  std::vector<CaseOverride> o;
  for (const auto& s : r.settings) o.push_back({s.key, s.value});
  for (size_t i = 0; i < plan.factors.size(); ++i) o.push_back({plan.factors[i].key, exact_number(x[i])});
  o.push_back({r.seed_key, std::to_string(seed)});
  return o;
}

std::vector<double> to_actual(const CampaignPlan& plan, const Eigen::VectorXd& coded) {
  std::vector<double> x;
  for (int j = 0; j < coded.size(); ++j) x.push_back(plan.factors[size_t(j)].to_actual(coded[j]));
  return x;
}

Eigen::VectorXd to_coded(const CampaignPlan& plan, const std::vector<double>& actual) {
  Eigen::VectorXd c(actual.size());
  for (size_t j = 0; j < actual.size(); ++j) c[int(j)] = plan.factors[j].to_coded(actual[j]);
  return c;
}

}  // namespace repose::calibrate
