#include "calibrate/design_analysis.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "calibrate/design_runs.h"
#include "calibrate/observations.h"
#include "calibrate/path_analysis.h"
#include "stats/anova.h"
#include "stats/calibration_curve.h"
#include "stats/errors.h"
#include "stats/optimize.h"
#include "stats/regression.h"
#include "stats/report.h"

namespace repose::calibrate {

namespace {

// The standard error of an OLS model's mean prediction, sqrt(ms m(c)' (X'X)^-1 m(c)), with the
// residual mean square `ms`; empty when the residual has no degrees of freedom.
std::function<double(const Eigen::VectorXd&)> prediction_sd(const std::vector<stats::Term>& terms, const Eigen::MatrixXd& x,
                                                            const Eigen::VectorXd& y, double ms, int df) {
  if (df <= 0 || !std::isfinite(ms)) return {};
  auto inverse = std::make_shared<Eigen::MatrixXd>(stats::least_squares(stats::model_matrix(terms, x), y).xtx_inverse);
  return [terms, inverse, ms](const Eigen::VectorXd& c) {
    Eigen::MatrixXd row = stats::model_matrix(terms, c.transpose());
    return std::sqrt(std::max(0.0, ms * (row * *inverse * row.transpose())(0, 0)));
  };
}

// One factor swept: a calibration curve of each response, its model for the posterior.
ResponseModel sweep_model(const CampaignPlan& plan, const Observations& obs, std::ostringstream& text,
                          std::shared_ptr<stats::CalibrationCurve>& curve_out) {
  const PlanFactor f = plan.factors[0];
  const int n = int(obs.y.size());
  std::vector<double> xs(static_cast<size_t>(n), 0.0), ys(static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    xs[size_t(i)] = f.to_actual(obs.x(i, 0));
    ys[size_t(i)] = obs.y[i];
  }
  auto curve = std::make_shared<stats::CalibrationCurve>(stats::fit_curve(xs, ys, plan.design.degree));
  curve_out = curve;
  const PlanResponse& r = plan.responses[size_t(obs.response)];
  text << "Calibration curve of " << r.label << " (degree " << curve->degree << ", R^2 = " << curve->r2 << "): " << r.name << " = ";
  for (int p = 0; p < curve->coefficients.size(); ++p)
    text << (p ? " + " : "") << curve->coefficients[p] << (p ? " " + f.name : "") << (p > 1 ? "^" + std::to_string(p) : "");
  text << "\n";
  std::vector<stats::Term> terms;
  for (int p = 0; p <= curve->degree; ++p) terms.push_back(stats::Term{{p}});
  double sse = 0;
  for (int i = 0; i < n; ++i) sse += std::pow(ys[size_t(i)] - (*curve)(xs[size_t(i)]), 2);
  const int df = n - (curve->degree + 1);
  ResponseModel m;
  m.response = obs.response;
  m.predict = [curve, f](const Eigen::VectorXd& c) { return (*curve)(f.to_actual(c[0])); };
  m.predict_sd = prediction_sd(terms, obs.x, obs.y, df > 0 ? sse / df : 0, df);
  return m;
}

// The sweep's answer: the curve inverted at the measured value (one response), or the swept value
// with the smallest expected miss (several; or when the curve cannot be inverted).
void analyse_sweep(const CampaignPlan& plan, const std::vector<Observations>& obs, CalibrationResult& res, std::ostringstream& text) {
  res.method = "calibration curve";
  std::shared_ptr<stats::CalibrationCurve> curve;
  for (const auto& o : obs) res.models.push_back(sweep_model(plan, o, text, curve));
  const PlanFactor f = plan.factors[0];
  double chosen = 0;
  bool inverted = false;
  if (obs.size() == 1) {
    try {
      chosen = f.to_coded(stats::invert(*curve, plan.primary().measured));
      inverted = true;
    } catch (const stats::StatsError& e) {
      text << "The curve cannot be inverted at " << plan.primary().measured << ": " << e.what() << "\n";
    }
  }
  if (!inverted) {
    double best = INFINITY;
    for (int s = 0; s <= 2000; ++s) {
      Eigen::VectorXd c = Eigen::VectorXd::Constant(1, -1 + s / 1000.0);
      const double j = expected_miss(plan, res.models, c);
      if (j < best) best = j, chosen = c[0];
    }
  }
  res.chosen_coded = Eigen::VectorXd::Constant(1, chosen);
}

// A response surface of one response (reduced backward when asked), with its ANOVA in `text`.
ResponseModel surface_model(const CampaignPlan& plan, const Observations& obs, std::ostringstream& text) {
  const int k = int(plan.factors.size());
  const PlanResponse& r = plan.responses[size_t(obs.response)];
  std::vector<stats::Term> terms = stats::build_model(stats::parse_model_kind(plan.design.model), k);
  std::vector<stats::RemovedTerm> removed;
  stats::ResponseSurface fit;
  if (plan.design.reduce > 0) {
    auto red = stats::reduce_backward(obs.x, obs.y, terms, plan.design.reduce, true);
    fit = red.model;
    removed = red.removed;
  } else {
    fit = stats::analyse(obs.x, obs.y, terms);
  }
  std::vector<std::string> names = plan.factor_names();
  std::vector<stats::Factor> ranges;
  for (const auto& f : plan.factors) ranges.push_back({f.name, f.low, f.high});
  if (plan.calibration_responses().size() > 1) text << "Response " << r.label << ":\n";
  text << stats::format_anova(fit, names, plan.design.model) << "\n" << stats::format_fit_statistics(fit) << "\n"
       << stats::format_equations(fit, r.name, names, ranges);
  for (const auto& rem : removed) text << "removed " << rem.term << " (p = " << stats::format_p(rem.p) << ")\n";
  auto model = std::make_shared<stats::ResponseSurface>(fit);
  ResponseModel m;
  m.response = obs.response;
  m.predict = [model](const Eigen::VectorXd& c) { return model->predict(c); };
  m.predict_sd = prediction_sd(fit.terms, obs.x, obs.y, fit.residual.ms, fit.residual.df);
  return m;
}

// The surfaces' answer, held factors fixed: one response is brought to its measured value
// (target optimisation inside the factorial cube); several minimise their expected miss.
void analyse_surface(const CampaignPlan& plan, const std::vector<Observations>& obs, CalibrationResult& res, std::ostringstream& text) {
  const int k = int(plan.factors.size());
  res.method = "response surface";
  for (const auto& o : obs) res.models.push_back(surface_model(plan, o, text));
  stats::Box box = stats::Box::cube(k, 1.0);
  for (auto [j, v] : held_factors(plan)) box.fix(j, v);
  stats::Optimum best;
  if (obs.size() == 1) {
    const PlanResponse& r = plan.primary();
    stats::OptimizeOptions opt;
    opt.tolerance = r.absolute_tolerance();
    best = stats::optimize(res.models[0].predict, box, {stats::GoalKind::target, r.measured}, opt);
    text << "\nNear-target set: " << best.set_size << " of " << best.sampled << " sampled points within +-" << opt.tolerance
         << " of " << r.measured << "\n";
  } else {
    const std::vector<ResponseModel> models = res.models;
    best = stats::optimize([&plan, models](const Eigen::VectorXd& c) { return expected_miss(plan, models, c); }, box,
                           {stats::GoalKind::minimize, 0});
  }
  if (!plan.design.fixed.empty()) {
    text << "Optimised with";
    for (auto [j, v] : plan.design.fixed) text << " " << plan.factors[size_t(j)].name << " = " << v;
    text << " held (design.fix).\n";
  }
  res.chosen_coded = best.x;
  double extent = 1;
  for (const auto& o : obs) extent = std::max(extent, o.x.cwiseAbs().maxCoeff());
  res.coded_extent = extent;
}

}  // namespace

std::vector<std::vector<double>> design_replicate_groups(const CampaignPlan& plan, const RunSource& source, int response) {
  return replicate_groups(observe(plan, source, design_runs(plan), response));
}

CalibrationResult analyse_design(const CampaignPlan& plan, const RunSource& source) {
  const std::vector<RunSpec> points = design_runs(plan);
  std::vector<Observations> obs;
  for (int r : plan.calibration_responses()) obs.push_back(observe(plan, source, points, r));
  if (plan.design.type == "path") return analyse_path(plan, obs);
  CalibrationResult res;
  std::ostringstream text;
  if (plan.design.type == "sweep") analyse_sweep(plan, obs, res, text);
  else analyse_surface(plan, obs, res, text);
  for (size_t i = 0; i < obs.size(); ++i) {
    ResponseModel& m = res.models[i];
    m.noise = pooled_noise(replicate_groups(obs[i]));
    m.runs = obs[i].runs;
    m.predicted = m.predict(res.chosen_coded);
    m.predicted_sd = m.predict_sd ? m.predict_sd(res.chosen_coded) : 0.0;
  }
  res.model_on_target = within_tolerance(plan, res.models, res.chosen_coded);
  describe_parameters(plan, res);
  add_posterior(plan, res);
  res.model_text = text.str();
  return res;
}

}  // namespace repose::calibrate
