#include "calibrate/design_runs.h"

#include <cstdio>

#include "stats/errors.h"

namespace repose::calibrate {

namespace {

std::vector<stats::Factor> stats_factors(const CampaignPlan& plan) {
  std::vector<stats::Factor> f;
  for (const auto& pf : plan.factors) f.push_back({pf.name, pf.low, pf.high});
  return f;
}

stats::Design sweep_design(const CampaignPlan& plan) {
  stats::Design d;
  d.type = "sweep";
  d.factors = stats_factors(plan);
  const int n = plan.design.levels;
  d.coded.resize(n, 1);
  for (int i = 0; i < n; ++i) {
    d.coded(i, 0) = -1.0 + 2.0 * i / (n - 1);
    d.points.push_back(stats::PointType::path);
    d.run_order.push_back(i);
  }
  return d;
}

// A design given as a table of actual factor values, one run per row (e.g. a paper's table).
stats::Design table_design(const CampaignPlan& plan) {
  stats::Design d;
  d.type = "table";
  d.factors = stats_factors(plan);
  const int n = int(plan.design.table_rows.size()), k = int(d.factors.size());
  d.coded.resize(n, k);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < k; ++j) d.coded(i, j) = d.factors[j].to_coded(plan.design.table_rows[i][j]);
    d.points.push_back(stats::PointType::factorial);
    d.run_order.push_back(i);
  }
  return d;
}

// A steepest-ascent path: `levels` points evenly from path_from to path_to (actual values).
stats::Design path_design(const CampaignPlan& plan) {
  stats::Design d;
  d.type = "path";
  d.factors = stats_factors(plan);
  const int n = plan.design.levels, k = int(d.factors.size());
  d.coded.resize(n, k);
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / (n - 1);
    for (int j = 0; j < k; ++j)
      d.coded(i, j) = d.factors[size_t(j)].to_coded(plan.design.path_from[size_t(j)] +
                                                     t * (plan.design.path_to[size_t(j)] - plan.design.path_from[size_t(j)]));
    d.points.push_back(stats::PointType::path);
    d.run_order.push_back(i);
  }
  return d;
}

}  // namespace

stats::Design build_design(const CampaignPlan& plan) {
  const auto& p = plan.design;
  std::vector<stats::Factor> f = stats_factors(plan);
  stats::Design d;
  if (p.type == "sweep") d = sweep_design(plan);
  else if (p.type == "table") d = table_design(plan);
  else if (p.type == "path") d = path_design(plan);
  else if (p.type == "ccd") d = stats::central_composite(f, stats::parse_alpha(p.alpha), p.centre);
  else if (p.type == "bbd") d = stats::box_behnken(f, p.centre);
  else if (p.type == "factorial") d = stats::full_factorial(f, p.centre);
  else if (p.type == "fractional") {
    auto gen = p.generators;
    if (gen.empty()) gen = stats::default_generators(int(f.size()), 1);
    d = stats::fractional_factorial(f, gen, p.centre);
  } else throw stats::DesignError("unknown design type '" + p.type + "'");
  if (p.order_seed != 0) stats::randomise_run_order(d, p.order_seed);
  return d;
}

std::vector<int> first_identical_rows(const stats::Design& d, int k) {
  std::vector<int> first(d.runs());
  for (int i = 0; i < d.runs(); ++i) {
    first[i] = i;
    for (int j = 0; j < i; ++j)
      if (d.coded.row(j).head(k) == d.coded.row(i).head(k)) {
        first[i] = first[j];
        break;
      }
  }
  return first;
}

std::vector<RunSpec> design_runs(const CampaignPlan& plan) {
  stats::Design d = build_design(plan);
  const int k = int(plan.factors.size());
  const int copies = plan.design.replicates;
  // Identical rows (centre points, repeated table rows) are one point run again: the c-th
  // occurrence takes replicates c*copies .. c*copies+copies-1, each its own packing seed.
  std::vector<int> first = first_identical_rows(d, k);
  std::vector<int> occurrence(d.runs(), 0);
  for (int i = 0; i < d.runs(); ++i)
    for (int j = 0; j < i; ++j)
      if (first[j] == first[i]) ++occurrence[i];
  std::vector<RunSpec> runs;
  for (int std_index : d.run_order) {
    std::vector<double> x(k);
    for (int j = 0; j < k; ++j) x[j] = d.actual(std_index, j);
    const int point = first[std_index] + 1;
    for (int r = occurrence[std_index] * copies; r < (occurrence[std_index] + 1) * copies; ++r) {
      char id[48];
      std::snprintf(id, sizeof id, "design-%03d-r%d", point, r);
      runs.push_back({id, "design", point, r, plan.base_seed + uint64_t(r), x});
    }
  }
  return runs;
}

std::vector<RunSpec> replicate_runs(const CampaignPlan& plan, const std::string& phase,
                                    const std::vector<double>& x, int first, int count) {
  std::vector<RunSpec> runs;
  for (int r = first; r < first + count; ++r)
    runs.push_back({phase + "-r" + std::to_string(r), phase, 0, r, plan.base_seed + uint64_t(r), x});
  return runs;
}

}  // namespace repose::calibrate
