// Reading a plan's [[factor]]s, its [design] (type, model, table, path, fixed factors) and its
// [adaptive] loop, each checked against the factors before anything runs (plan_reading.h).
#include <toml++/toml.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "calibrate/design_runs.h"
#include "calibrate/plan_reading.h"
#include "stats/csv_table.h"
#include "stats/errors.h"
#include "stats/model_terms.h"
#include "stats/regression.h"
#include "util/number_text.h"

namespace repose::calibrate {

namespace fs = std::filesystem;

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

namespace {

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

}  // namespace

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

}  // namespace repose::calibrate
