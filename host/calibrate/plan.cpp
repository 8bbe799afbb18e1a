#include "calibrate/plan.h"

#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <algorithm>
#include <iterator>
#include <sstream>

#include "calibrate/design_runs.h"
#include "calibrate/experiment_runner.h"
#include "case/toml_section.h"
#include "stats/csv_table.h"
#include "stats/errors.h"
#include "stats/model_terms.h"
#include "stats/regression.h"
#include "util/hash.h"
#include "util/input_file.h"
#include "util/number_text.h"
#include "util/path_name.h"

namespace repose::calibrate {

namespace {

namespace fs = std::filesystem;

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

// A TOML value as override text: strings bare, everything else as TOML writes it.
std::string value_text(const toml::node& node) {
  if (auto s = node.value<std::string>(); s && node.is_string()) return *s;
  if (node.is_floating_point()) return exact_number(*node.value<double>());
  std::ostringstream out;
  node.visit([&](auto&& v) { out << v; });
  return out.str();
}

bool valid_name(const std::string& n) {
  if (n.empty() || !(std::isalpha((unsigned char)n[0]) || n[0] == '_')) return false;
  for (char c : n)
    if (!(std::isalnum((unsigned char)c) || c == '_')) return false;
  return true;
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

void read_factors(const toml::node& node, const std::string& file, CampaignPlan& plan) {
  const toml::array* list = node.as_array();
  if (!list || !list->is_array_of_tables())
    throw CaseError({file, "factor", int(node.source().begin.line)}, "expected [[factor]] tables");
  std::set<std::string> names, keys;
  for (size_t i = 0; i < list->size(); ++i) {
    const toml::table& ft = *list->get(i)->as_table();
    PlanTable t(ft, file, "factor." + std::to_string(i));
    t.allow_only({"name", "key", "low", "high"});
    PlanFactor f;
    f.key = t.required_text("key");
    f.name = t.text("name").value_or(f.key.substr(f.key.rfind('.') + 1));
    PlanTable named(ft, file, "factor." + f.name);
    if (!valid_name(f.name)) named.fail("name", "'" + f.name + "': use letters, digits and _, starting with a letter");
    if (!names.insert(f.name).second) named.fail("name", "a factor named '" + f.name + "' is listed twice");
    if (!keys.insert(f.key).second) named.fail("key", "'" + f.key + "' is already a factor");
    f.low = named.required_number("low");
    f.high = named.required_number("high");
    if (!(f.low < f.high))
      named.fail("high", "range reversed or empty: low = " + format_number(f.low) + " must be below high = " + format_number(f.high));
    f.where = named.where("key");
    plan.factors.push_back(f);
  }
  if (plan.factors.empty()) throw CaseError({file, "factor", int(node.source().begin.line)}, "no factor");
}

// type = "table": the runs are the rows of a CSV (path relative to the plan), one column per factor.
void read_design_table(const PlanTable& t, CampaignPlan& plan) {
  DesignPlan& d = plan.design;
  std::string rel = t.required_text("table");
  fs::path p = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(plan.path).parent_path() / rel;
  d.table = p.lexically_normal().string();
  try {
    stats::Table table = stats::read_csv(d.table);
    std::vector<std::vector<double>> columns;
    for (const auto& f : plan.factors) columns.push_back(table.numeric_column(f.name));
    for (int r = 0; r < table.rows(); ++r) {
      std::vector<double> row;
      for (const auto& c : columns) row.push_back(c[size_t(r)]);
      d.table_rows.push_back(row);
    }
    if (d.table_rows.empty()) throw stats::TableError(d.table, 0, 0, "no runs in the table");
  } catch (const InputError& e) {
    t.fail("table", std::string("design table: ") + e.what());
  }
}

// The design's model can be fitted from its runs: a known model, enough distinct points, and a
// model matrix of full rank.
void check_model_estimable(const PlanTable& t, const CampaignPlan& plan) {
  const DesignPlan& d = plan.design;
  const int k = int(plan.factors.size());
  stats::ModelKind kind;
  try {
    kind = stats::parse_model_kind(d.model);
  } catch (const std::exception& e) {
    t.fail("model", e.what());
  }
  std::vector<stats::Term> terms = stats::build_model(kind, k);
  stats::Design design;
  try {
    design = build_design(plan);
  } catch (const std::exception& e) {
    t.fail(std::string(e.what()));
  }
  // The model must be estimable from the design's distinct points (replicates add no rank).
  std::vector<int> first = first_identical_rows(design, k);
  int distinct = 0;
  for (int i = 0; i < design.runs(); ++i) distinct += first[i] == i;
  if (distinct < int(terms.size()))
    t.fail("model", "fewer runs than model terms: a " + d.model + " model in " + std::to_string(k) + " factors has " +
                        std::to_string(terms.size()) + " terms, the " + d.type + " design gives " +
                        std::to_string(distinct) + " distinct points");
  try {
    Eigen::MatrixXd x = design.coded.leftCols(k);
    std::vector<std::string> term_names;
    for (const auto& term : terms) term_names.push_back(stats::term_name(term));
    stats::least_squares(stats::model_matrix(terms, x), Eigen::VectorXd::Zero(x.rows()), term_names);
  } catch (const stats::StatsError& e) {
    t.fail("model", std::string("the ") + d.type + " design cannot estimate this model: " + e.what());
  }
}

// An inline table of actual values by factor name, e.g. from = { e = 0.38, mu_s = 0.1 }.
std::vector<std::pair<int, double>> factor_values(const PlanTable& t, const std::string& key, const CampaignPlan& plan) {
  std::vector<std::pair<int, double>> out;
  const toml::node* node = t.table().get(key);
  if (!node) return out;
  if (!node->is_table()) t.fail(key, "expected a table of factor values, e.g. " + key + " = { " + plan.factors[0].name + " = 0.4 }");
  PlanTable values(*node->as_table(), t.file(), t.prefix() + "." + key);
  for (auto&& [k, v] : *node->as_table()) {
    int index = -1;
    for (size_t j = 0; j < plan.factors.size(); ++j)
      if (plan.factors[j].name == k.str()) index = int(j);
    if (index < 0) values.fail(k.str(), "no factor named '" + std::string(k.str()) + "'");
    const PlanFactor& f = plan.factors[size_t(index)];
    double x = values.required_number(k.str());
    if (x < f.low || x > f.high)
      values.fail(k.str(), format_number(x) + " lies outside the factor's range " + format_number(f.low) + " .. " + format_number(f.high));
    out.push_back({index, x});
  }
  return out;
}

// type = "path": `levels` points evenly from `from` to `to` (default every factor's low and high).
void read_path(const PlanTable& t, CampaignPlan& plan) {
  DesignPlan& d = plan.design;
  d.path_from.clear();
  d.path_to.clear();
  for (const auto& f : plan.factors) {
    d.path_from.push_back(f.low);
    d.path_to.push_back(f.high);
  }
  for (auto [j, v] : factor_values(t, "from", plan)) d.path_from[size_t(j)] = v;
  for (auto [j, v] : factor_values(t, "to", plan)) d.path_to[size_t(j)] = v;
  if (d.path_from == d.path_to) t.fail("to", "the path has no length: from and to are the same point");
}

void read_design(const PlanTable& t, CampaignPlan& plan) {
  t.allow_only({"type", "alpha", "centre", "replicates", "model", "reduce", "generators", "levels", "degree", "order_seed", "table",
                "from", "to", "fix"});
  DesignPlan& d = plan.design;
  d.type = t.text("type").value_or("ccd");
  const std::set<std::string> types = {"ccd", "bbd", "factorial", "fractional", "sweep", "table", "path"};
  if (!types.count(d.type)) t.fail("type", "unknown design '" + d.type + "' (ccd, bbd, factorial, fractional, sweep, table, path)");
  if (d.type != "path")
    for (const char* key : {"from", "to"})
      if (t.has(key)) t.fail(key, "a path's end: needs type = \"path\"");
  if (d.type == "table") {
    read_design_table(t, plan);
  } else if (t.table().get("table")) {
    t.fail("table", "a design table needs type = \"table\"");
  }
  d.alpha = t.text("alpha").value_or("rotatable");
  d.centre = t.integer_at_least("centre", d.type == "sweep" || d.type == "path" ? 0 : 3, 0);
  d.replicates = t.integer_at_least("replicates", 1, 1);
  d.model = t.text("model").value_or(d.type == "ccd" || d.type == "bbd" ? "quadratic" : "linear");
  d.levels = t.integer_at_least("levels", 5, 2);
  d.degree = t.integer_at_least("degree", 3, 1);
  d.order_seed = uint64_t(t.integer_at_least("order_seed", 0, 0));
  if (auto r = t.number("reduce")) {
    if (!(*r > 0 && *r < 1)) t.fail("reduce", "a p-value threshold in (0, 1), e.g. 0.1");
    d.reduce = *r;
  }
  if (const toml::node* g = t.table().get("generators")) {
    const toml::array* a = g->as_array();
    if (!a) t.fail("generators", "expected an array of strings like [\"C=AB\"]");
    for (const auto& e : *a) {
      if (!e.is_string()) t.fail("generators", "expected strings like \"C=AB\"");
      d.generators.push_back(*e.value<std::string>());
    }
  }
  const int k = int(plan.factors.size());
  d.fixed = factor_values(t, "fix", plan);
  if (!d.fixed.empty() && (d.type == "sweep" || d.type == "path"))
    t.fail("fix", "a " + d.type + " fits no surface to optimise: fix factors of a ccd, bbd or factorial design");
  if (int(d.fixed.size()) >= k) t.fail("fix", "every factor is fixed: nothing is left to calibrate");
  if (d.type == "path") {
    if (t.has("model")) t.fail("model", "a path (steepest ascent) fits no model: its best point is chosen");
    if (d.levels < 2) t.fail("levels", "a path needs at least 2 points");
    read_path(t, plan);
    return;
  }
  if (d.type == "sweep") {
    if (k != 1) t.fail("type", "a sweep (calibration curve) takes exactly one factor; the plan has " + std::to_string(k));
    if (d.levels < d.degree + 1)
      t.fail("levels", std::to_string(d.levels) + " levels cannot fit a degree-" + std::to_string(d.degree) +
                           " calibration curve (fewer runs than model terms: needs at least " + std::to_string(d.degree + 1) + ")");
    return;
  }
  if (d.type == "ccd" && k < 2) t.fail("type", "a central composite design needs at least 2 factors (use type = \"sweep\" for one)");
  if (d.type == "bbd" && (k < 3 || k > 7)) t.fail("type", "a Box-Behnken design takes 3 to 7 factors");
  check_model_estimable(t, plan);
}

void read_adaptive(const PlanTable& t, CampaignPlan& plan) {
  t.allow_only({"initial", "budget", "seeds", "pilot", "pilot_points"});
  const int k = int(plan.factors.size());
  plan.adaptive.initial = t.integer_at_least("initial", 2 * k + 1, 2);
  plan.adaptive.budget = t.integer_at_least("budget", 20, 2);
  if (plan.adaptive.budget < plan.adaptive.initial)
    t.fail("budget", "budget " + std::to_string(plan.adaptive.budget) + " is below the " +
                         std::to_string(plan.adaptive.initial) + " initial runs");
  if (auto seeds = t.text("seeds")) {
    if (*seeds != "same" && *seeds != "per_run")
      t.fail("seeds", "expected \"same\" (every run packs with base_seed) or \"per_run\", got \"" + *seeds + "\"");
    plan.adaptive.seed_per_run = *seeds == "per_run";
  }
  // Runs that differ by their packing seed are noisy: the noise is measured by a pilot, never
  // assumed, so the surrogate cannot draw a noise-free curve through a handful of heaps.
  plan.adaptive.pilot = t.integer_at_least("pilot", plan.adaptive.seed_per_run ? 4 : 0, 0);
  plan.adaptive.pilot_points = t.integer_at_least("pilot_points", 1, 1);
  if (plan.adaptive.pilot_points > 2) t.fail("pilot_points", "1 (the centre) or 2 (coded -0.5 and +0.5 on the diagonal)");
  if (plan.adaptive.seed_per_run && plan.adaptive.pilot < 2)
    t.fail("pilot", "seeds = \"per_run\" makes every run noisy: the noise must be measured by a pilot of at least 2 fills "
                    "(default 4) at the centre");
  if (plan.adaptive.pilot == 1) t.fail("pilot", "one fill measures no noise: at least 2, or 0 for none");
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
  rig.case_identity = spec.identity;
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
  kv["verification.runs"] = std::to_string(p.verification_runs);
  std::string text;
  for (const auto& [k, v] : kv) text += k + " = " + v + "\n";
  // The base case as parsed, line by line, so a change can be named (describe_plan_change).
  std::istringstream identity(main.case_identity);
  for (std::string line; std::getline(identity, line);)
    if (!line.empty()) text += kCaseLinePrefix + line + "\n";
  return text;
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
