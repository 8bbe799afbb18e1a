#include "calibrate/report_figures.h"

#include <algorithm>
#include <cmath>

#include "calibrate/campaign.h"
#include "calibrate/observations.h"
#include "plot/chart.h"
#include "util/number_text.h"
#include "util/units.h"

namespace repose::calibrate {

std::string factor_label(const PlanFactor& f) {
  std::string unit = quantity_unit(f.key);
  return unit.empty() ? f.name : f.name + " (" + unit + ")";
}

namespace {

struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) {
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  void pad(double fraction) {
    double d = (hi - lo) * fraction;
    if (d == 0) d = std::abs(hi) * 0.02 + 1e-12;
    lo -= d;
    hi += d;
  }
};

// A run axis (1 .. n) wide enough that its ticks fall on whole runs.
double run_axis_end(size_t n) { return double(std::max<size_t>(n, 6)) + 0.5; }

Figure contour(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  const PlanFactor &fa = plan.factors[0], &fb = plan.factors[1];
  const ResponseModel& model = res.primary();
  const PlanResponse& resp = plan.responses[size_t(model.response)];
  // A margin beyond the outermost runs (axial points) so none sits on the frame.
  const double e = res.coded_extent * 1.08;
  Chart chart(900, 700, fa.to_actual(-e), fa.to_actual(e), fb.to_actual(-e), fb.to_actual(e), true);
  auto at = [&](double a, double b) {
    Eigen::VectorXd c = res.chosen_coded;
    c[0] = fa.to_coded(a);
    c[1] = fb.to_coded(b);
    return model.predict(c);
  };
  Range r;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) r.add(at(fa.to_actual(-e + 2 * e * i / 40), fb.to_actual(-e + 2 * e * j / 40)));
  std::vector<double> levels;
  for (int i = 1; i < 10; ++i) levels.push_back(r.lo + (r.hi - r.lo) * i / 10);
  chart.response_map(at, levels, {resp.measured}, quantity_label(resp.name));
  for (const auto& run : model.runs) chart.marker(run.spec.x[0], run.spec.x[1], colours::black, 5);
  chart.cross(res.chosen[0], res.chosen[1], colours::red, 9);
  chart.title(resp.label + ": model over " + fa.name + ", " + fb.name);
  chart.labels(factor_label(fa), factor_label(fb));
  chart.legend_above({{"measured " + resp.name + " (contour)", colours::black, Mark::Line},
                      {"runs", colours::black, Mark::Dot},
                      {"chosen point", colours::red, Mark::Cross}});
  chart.save(dir + "/contour.png");
  std::string others = plan.factors.size() > 2 ? " (other factors at their chosen values)" : "";
  return {"contour.png", "Response surface of " + resp.label + " over " + fa.name + " and " + fb.name + others +
                             ": colours as the bar shows, grey lines every tenth of its range, black the measured value, dots the "
                             "runs, red cross the chosen point."};
}

Figure main_effects(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  const int k = int(plan.factors.size());
  const ResponseModel& model = res.primary();
  const PlanResponse& resp = plan.responses[size_t(model.response)];
  const double e = res.coded_extent;
  Range r;
  std::vector<std::vector<double>> ys(static_cast<size_t>(k));
  std::vector<double> xs;
  for (int i = 0; i <= 60; ++i) xs.push_back(-e + 2 * e * i / 60);
  for (int j = 0; j < k; ++j)
    for (double c : xs) {
      Eigen::VectorXd p = Eigen::VectorXd::Zero(k);
      p[j] = c;
      ys[size_t(j)].push_back(model.predict(p));
      r.add(ys[size_t(j)].back());
    }
  r.add(resp.measured);
  r.pad(0.08);
  Chart chart(860, 560, -e, e, r.lo, r.hi);
  std::vector<LegendEntry> legend;
  for (int j = 0; j < k; ++j) {
    Colour c = colours::series()[size_t(j) % colours::series().size()];
    chart.polyline(xs, ys[size_t(j)], c, 3);
    legend.push_back({plan.factors[size_t(j)].name, c, Mark::Line});
  }
  chart.horizontal(resp.measured, colours::black, 1);
  legend.push_back({"measured " + resp.name, colours::black, Mark::Line});
  chart.title("Main effects on " + resp.label + " (others at the centre)");
  chart.labels("coded factor level (-1 = low, +1 = high)", quantity_label(resp.name));
  chart.legend(legend);
  chart.save(dir + "/main_effects.png");
  return {"main_effects.png", "Main effects: the model's " + resp.label +
                                  " as each factor moves over its coded range with the others at the design centre; black line: measured."};
}

Figure calibration_curve(const CampaignPlan& plan, const CalibrationResult& res, int j, const std::string& dir) {
  const PlanFactor& f = plan.factors[size_t(j)];
  const ResponseModel& model = res.primary();
  const PlanResponse& resp = plan.responses[size_t(model.response)];
  const double e = res.coded_extent, tol = resp.absolute_tolerance();
  std::vector<double> xs, ys, lo, hi;
  Range r;
  for (int i = 0; i <= 100; ++i) {
    Eigen::VectorXd c = res.chosen_coded;
    c[j] = -e + 2 * e * i / 100;
    xs.push_back(f.to_actual(c[j]));
    ys.push_back(model.predict(c));
    double s = model.predict_sd ? model.predict_sd(c) : 0;
    lo.push_back(ys.back() - 2 * s);
    hi.push_back(ys.back() + 2 * s);
    r.add(ys.back());
  }
  // Runs shown are those sharing the chosen values of the other factors (all runs for one factor).
  std::vector<const RunRecord*> shown;
  for (const auto& run : model.runs) {
    bool on_line = true;
    for (size_t m = 0; m < plan.factors.size(); ++m)
      if (int(m) != j && std::abs(plan.factors[m].to_coded(run.spec.x[m]) - res.chosen_coded[int(m)]) > 1e-6) on_line = false;
    if (on_line || plan.factors.size() == 1) shown.push_back(&run);
  }
  for (auto* run : shown) r.add(response_value(*run, resp.name));
  // The measured value's band never fills the plot: it takes at most half its height.
  r.add(resp.measured - 2 * tol);
  r.add(resp.measured + 2 * tol);
  r.pad(0.08);
  Chart chart(860, 560, xs.front(), xs.back(), r.lo, r.hi);
  chart.horizontal_band(resp.measured - tol, resp.measured + tol, colours::green);
  std::vector<LegendEntry> legend = {{"model", colours::blue, Mark::Line}};
  if (model.predict_sd) {
    chart.band(xs, lo, hi, colours::blue);
    legend.push_back({"model +- 2 sd", colours::blue, Mark::Band});
  }
  chart.polyline(xs, ys, colours::blue, 3);
  chart.horizontal(resp.measured, colours::green, 2);
  legend.push_back({"measured", colours::green, Mark::Line});
  legend.push_back({"+- tolerance", colours::green, Mark::Band});
  for (auto* run : shown) chart.marker(run->spec.x[size_t(j)], response_value(*run, resp.name), colours::black, 4);
  chart.vertical(res.chosen[size_t(j)], colours::red, 2);
  legend.push_back({"chosen " + f.name, colours::red, Mark::Line});
  if (!shown.empty()) legend.push_back({"simulated runs", colours::black, Mark::Dot});
  chart.title("Calibration curve: " + resp.label + " vs " + f.name);
  chart.labels(factor_label(f) + ", " + f.key, quantity_label(resp.name));
  chart.legend(legend);
  const std::string file = "calibration_" + f.name + ".png";
  chart.save(dir + "/" + file);
  std::string caption = "Calibration curve of " + f.name + ": the model's " + resp.label + " along " + f.name;
  if (plan.factors.size() > 1) caption += " with the other factors at their chosen values";
  if (model.predict_sd) caption += " (band: +-2 sd of the model's mean)";
  return {file, caption + "; green: measured value and tolerance; red: chosen value; dots: runs on this line."};
}

Figure predicted_vs_simulated(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  const ResponseModel& model = res.primary();
  const PlanResponse& resp = plan.responses[size_t(model.response)];
  Range r;
  std::vector<std::pair<double, double>> pts, verified;
  for (const auto& run : model.runs) {
    pts.push_back({response_value(run, resp.name), model.predict(to_coded(plan, run.spec.x))});
    r.add(pts.back().first);
    r.add(pts.back().second);
  }
  for (const auto& c : res.checks)
    if (c.response == model.response)
      for (const auto& v : c.runs) {
        verified.push_back({response_value(v, resp.name), model.predicted});
        r.add(verified.back().first);
        r.add(verified.back().second);
      }
  r.pad(0.08);
  Chart chart(760, 700, r.lo, r.hi, r.lo, r.hi);
  chart.polyline({r.lo, r.hi}, {r.lo, r.hi}, colours::grey, 1);
  for (const auto& [s, p] : pts) chart.marker(s, p, colours::blue, 4);
  for (const auto& [s, p] : verified) chart.marker(s, p, colours::red, 5);
  chart.title("Predicted vs simulated " + resp.label);
  chart.labels("simulated " + quantity_label(resp.name), "predicted " + quantity_label(resp.name));
  std::vector<LegendEntry> legend = {{"model runs", colours::blue, Mark::Dot}, {"predicted = simulated", colours::grey, Mark::Line}};
  if (!verified.empty()) legend.push_back({"verification", colours::red, Mark::Dot});
  chart.legend(legend);
  chart.save(dir + "/predicted_vs_simulated.png");
  return {"predicted_vs_simulated.png", "Predicted against simulated " + resp.label +
                                            " for the runs the model was fitted to (blue) and the verification runs (red); "
                                            "the runs' noise spreads them about the grey line."};
}

Figure verification(const CampaignPlan& plan, const CalibrationResult& res, const ResponseCheck& c, bool first,
                    const std::string& dir) {
  const PlanResponse& resp = plan.responses[size_t(c.response)];
  Range r;
  const double tol = c.tolerance;
  r.add(resp.measured - 2 * tol);
  r.add(resp.measured + 2 * tol);
  std::vector<double> values;
  for (const auto& v : c.runs) values.push_back(response_value(v, resp.name));
  for (double v : values) r.add(v);
  if (std::isfinite(c.se)) {
    r.add(c.mean - c.se);
    r.add(c.mean + c.se);
  }
  r.pad(0.1);
  r.hi += 0.3 * (r.hi - r.lo);  // headroom for the legend: the band spans the width, so no corner is clear of it
  const int n = int(values.size());
  Chart chart(860, 540, 0.5, run_axis_end(size_t(n)), r.lo, r.hi);
  chart.horizontal_band(resp.measured - tol, resp.measured + tol, colours::green);
  chart.horizontal(resp.measured, colours::green, 2);
  chart.horizontal(c.mean, colours::red, 1);
  if (std::isfinite(c.se)) chart.error_bar(0.5 * (1 + n), c.mean - c.se, c.mean + c.se, colours::red);
  for (int i = 0; i < n; ++i) chart.marker(i + 1, values[size_t(i)], colours::red, 5);
  chart.title("Verification of " + resp.label + ": " + agreement_name(c.agreement));
  chart.subtitle(res.target_reached ? "campaign: target reached" : "campaign: target NOT reached");
  chart.labels("verification run (each its own packing seed)", quantity_label(resp.name));
  chart.legend({{"measured", colours::green, Mark::Line}, {"+- tolerance", colours::green, Mark::Band},
                {"runs", colours::red, Mark::Dot}, {"their mean (bar: +- 1 SE)", colours::red, Mark::Line}});
  const std::string file = first ? "verification.png" : "verification_" + resp.label + ".png";
  chart.save(dir + "/" + file);
  return {file, "The verification runs of " + resp.label + " (each its own packing seed) against the measured value and its "
                    "tolerance band; red line their mean, bar its standard error. " + check_text(plan, c) + "."};
}

// A steepest-ascent path: each point's mean (bar: +- 1 SE) and its runs, against the measured value.
Figure path_figure(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  const ResponseModel& model = res.primary();
  const PlanResponse& resp = plan.responses[size_t(model.response)];
  const double tol = resp.absolute_tolerance();
  Range r;
  r.add(resp.measured - 2 * tol);
  r.add(resp.measured + 2 * tol);
  std::vector<std::pair<double, double>> runs;
  for (const auto& run : model.runs) {
    const Eigen::VectorXd c = to_coded(plan, run.spec.x);
    for (size_t p = 0; p < res.path.size(); ++p)
      if ((res.path[p].coded - c).norm() < 1e-9) runs.push_back({double(p + 1), response_value(run, resp.name)});
  }
  for (const auto& [x, y] : runs) r.add(y);
  r.pad(0.08);
  Chart chart(860, 560, 0.5, run_axis_end(res.path.size()), r.lo, r.hi);
  chart.horizontal_band(resp.measured - tol, resp.measured + tol, colours::green);
  chart.horizontal(resp.measured, colours::green, 2);
  for (const auto& [x, y] : runs) chart.marker(x, y, colours::grey, 3);
  std::vector<double> xs, means;
  size_t chosen = 0;
  for (size_t p = 0; p < res.path.size(); ++p) {
    xs.push_back(double(p + 1));
    means.push_back(res.path[p].mean[0]);
    if (std::isfinite(res.path[p].se[0]))
      chart.error_bar(double(p + 1), means.back() - res.path[p].se[0], means.back() + res.path[p].se[0], colours::blue);
    if ((res.path[p].coded - res.chosen_coded).norm() < 1e-12) chosen = p;
  }
  chart.polyline(xs, means, colours::blue, 2);
  for (size_t p = 0; p < xs.size(); ++p) chart.square(xs[p], means[p], colours::blue, 4);
  chart.cross(xs[chosen], means[chosen], colours::red, 9);
  std::string axis = "path point (";
  for (size_t j = 0; j < plan.factors.size(); ++j)
    axis += (j ? ", " : "") + plan.factors[j].name + " " + format_g(plan.factors[j].to_actual(res.path.front().coded[int(j)]), 3) +
            " -> " + format_g(plan.factors[j].to_actual(res.path.back().coded[int(j)]), 3);
  chart.title("Steepest-ascent path: " + resp.label + " at each point");
  chart.labels(axis + ")", quantity_label(resp.name));
  chart.legend({{"measured", colours::green, Mark::Line}, {"+- tolerance", colours::green, Mark::Band},
                {"runs", colours::grey, Mark::Dot}, {"mean of the runs (bar: +- 1 SE)", colours::blue, Mark::Square},
                {"chosen point", colours::red, Mark::Cross}});
  chart.save(dir + "/path.png");
  return {"path.png", "The steepest-ascent path: each point's runs (grey), their mean with its standard error (blue), the "
                      "measured value and its tolerance (green), and the chosen point (red cross). No model is fitted."};
}

}  // namespace

std::vector<Figure> write_figures(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  std::vector<Figure> out;
  if (!res.path.empty()) {
    out.push_back(path_figure(plan, res, dir));
  } else {
    if (plan.factors.size() >= 2) {
      out.push_back(contour(plan, res, dir));
      out.push_back(main_effects(plan, res, dir));
    }
    for (int j = 0; j < int(plan.factors.size()); ++j) out.push_back(calibration_curve(plan, res, j, dir));
    out.push_back(predicted_vs_simulated(plan, res, dir));
    for (const auto& f : posterior_figures(plan, res, dir)) out.push_back(f);
  }
  for (size_t i = 0; i < res.checks.size(); ++i)
    if (!res.checks[i].runs.empty()) out.push_back(verification(plan, res, res.checks[i], i == 0, dir));
  return out;
}

Figure write_convergence_figure(const CampaignPlan& plan, const AdaptiveOutcome& loop, const std::string& dir) {
  std::vector<double> xs, best, each;
  double b = INFINITY;
  Range r;
  for (size_t i = 0; i < loop.steps.size(); ++i) {
    double e = 100 * std::abs(loop.steps[i].relative_error);
    b = std::min(b, e);
    xs.push_back(double(i + 1));
    best.push_back(b);
    each.push_back(e);
    r.add(e);
  }
  r.add(0);
  r.add(100 * plan.primary().tolerance);
  r.pad(0.05);
  r.hi += 0.3 * (r.hi - r.lo);  // room above the runs for the legend: noisy runs fill every corner
  Chart chart(860, 540, 0.5, run_axis_end(xs.size()), 0, r.hi);
  chart.horizontal(100 * plan.primary().tolerance, colours::green, 2);
  std::vector<LegendEntry> legend = {{"best run so far", colours::blue, Mark::Line}, {"tolerance", colours::green, Mark::Line},
                                     {"each run", colours::black, Mark::Dot}};
  const bool proposals = int(loop.steps.size()) > loop.initial;
  if (proposals) {
    chart.vertical(loop.initial + 0.5, colours::grey, 2);
    legend.push_back({"start | proposals", colours::grey, Mark::Line});
  }
  chart.polyline(xs, best, colours::blue, 3);
  for (size_t i = 0; i < xs.size(); ++i) chart.marker(xs[i], each[i], colours::black, 4);
  chart.title("Adaptive loop: error of each run and best so far");
  chart.labels("loop run", "error of " + plan.primary().label + " (%)");
  chart.legend(legend);
  chart.save(dir + "/convergence.png");
  return {"convergence.png", std::string("Relative error of each run of the loop (dots) and the best so far (blue)") +
                                 (proposals ? "; left of the grey line the space-filling start, right of it the proposals"
                                            : "; every run is of the space-filling start (no proposal was needed)") +
                                 "; green: the tolerance. A single noisy run near the tolerance proves nothing: the loop "
                                 "stops on the surrogate's mean, and the verification decides."};
}

}  // namespace repose::calibrate
