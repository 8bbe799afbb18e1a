#include "calibrate/report_figures.h"

#include <algorithm>
#include <cmath>

#include "plot/chart.h"
#include "util/units.h"

namespace repose::calibrate {

namespace {

double actual(const PlanFactor& f, double coded) { return 0.5 * (f.low + f.high) + coded * 0.5 * (f.high - f.low); }
double coded(const PlanFactor& f, double a) { return (a - 0.5 * (f.low + f.high)) / (0.5 * (f.high - f.low)); }
double response(const RunRecord& r, const std::string& name) { return r.responses.at(name); }
// "e", "G (Pa)": a factor's name with the unit of its case key.
std::string factor_label(const PlanFactor& f) {
  std::string unit = quantity_unit(f.key);
  return unit.empty() ? f.name : f.name + " (" + unit + ")";
}

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

Figure contour(const CampaignPlan& plan, const CalibrationResult& res, const std::vector<RunRecord>& runs,
               const std::string& dir) {
  const PlanFactor &fa = plan.factors[0], &fb = plan.factors[1];
  // A margin beyond the outermost runs (axial points) so none sits on the frame.
  const double e = res.coded_extent * 1.08;
  Chart chart(900, 700, actual(fa, -e), actual(fa, e), actual(fb, -e), actual(fb, e), true);
  auto at = [&](double a, double b) {
    Eigen::VectorXd c = res.chosen_coded;
    c[0] = coded(fa, a);
    c[1] = coded(fb, b);
    return res.predict(c);
  };
  Range r;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) r.add(at(actual(fa, -e + 2 * e * i / 40), actual(fb, -e + 2 * e * j / 40)));
  std::vector<double> levels;
  for (int i = 1; i < 10; ++i) levels.push_back(r.lo + (r.hi - r.lo) * i / 10);
  chart.response_map(at, levels, {plan.measured}, quantity_label(plan.response));
  for (const auto& run : runs) chart.marker(run.spec.x[0], run.spec.x[1], colours::black, 5);
  chart.cross(res.chosen[0], res.chosen[1], colours::red, 9);
  chart.title(plan.response + ": model over " + fa.name + ", " + fb.name);
  chart.labels(factor_label(fa), factor_label(fb));
  chart.legend_above({{"measured " + plan.response + " (contour)", colours::black}, {"runs", colours::black},
                      {"chosen point", colours::red}});
  chart.save(dir + "/contour.png");
  std::string others = plan.factors.size() > 2 ? " (other factors at their calibrated values)" : "";
  return {"contour.png", "Response surface of " + plan.response + " over " + fa.name + " and " + fb.name + others +
                             ": colours as the bar shows, grey lines every tenth of its range, black the measured value, dots the "
                             "runs, red cross the chosen point."};
}

Figure main_effects(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  const int k = int(plan.factors.size());
  const double e = res.coded_extent;
  Range r;
  std::vector<std::vector<double>> ys(k);
  std::vector<double> xs;
  for (int i = 0; i <= 60; ++i) xs.push_back(-e + 2 * e * i / 60);
  for (int j = 0; j < k; ++j)
    for (double c : xs) {
      Eigen::VectorXd p = Eigen::VectorXd::Zero(k);
      p[j] = c;
      ys[j].push_back(res.predict(p));
      r.add(ys[j].back());
    }
  r.add(plan.measured);
  r.pad(0.08);
  Chart chart(860, 560, -e, e, r.lo, r.hi);
  std::vector<LegendEntry> legend;
  for (int j = 0; j < k; ++j) {
    Colour c = colours::series()[j % colours::series().size()];
    chart.polyline(xs, ys[j], c, 3);
    legend.push_back({plan.factors[j].name, c});
  }
  chart.horizontal(plan.measured, colours::black, 1);
  chart.title("Main effects on " + plan.response + " (others at the centre)");
  chart.labels("coded factor level (-1 = low, +1 = high)", quantity_label(plan.response));
  chart.legend(legend);
  chart.save(dir + "/main_effects.png");
  return {"main_effects.png", "Main effects: the model's " + plan.response +
                                  " as each factor moves over its coded range with the others at the design centre; black line: measured."};
}

Figure calibration_curve(const CampaignPlan& plan, const CalibrationResult& res, const std::vector<RunRecord>& runs, int j,
                         const std::string& dir) {
  const PlanFactor& f = plan.factors[j];
  const double e = res.coded_extent;
  std::vector<double> xs, ys, lo, hi;
  Range r;
  for (int i = 0; i <= 100; ++i) {
    Eigen::VectorXd c = res.chosen_coded;
    c[j] = -e + 2 * e * i / 100;
    xs.push_back(actual(f, c[j]));
    ys.push_back(res.predict(c));
    double s = res.predict_sd ? res.predict_sd(c) : 0;
    lo.push_back(ys.back() - 2 * s);
    hi.push_back(ys.back() + 2 * s);
    r.add(ys.back());
  }
  // Runs shown are those sharing the chosen values of the other factors (all runs for one factor).
  std::vector<const RunRecord*> shown;
  for (const auto& run : runs) {
    bool on_line = true;
    for (size_t m = 0; m < plan.factors.size(); ++m)
      if (int(m) != j && std::abs(coded(plan.factors[m], run.spec.x[m]) - res.chosen_coded[m]) > 1e-6) on_line = false;
    if (on_line || plan.factors.size() == 1) shown.push_back(&run);
  }
  for (auto* run : shown) r.add(response(*run, plan.response));
  r.add(plan.measured);
  r.pad(0.08);
  Chart chart(860, 560, xs.front(), xs.back(), r.lo, r.hi);
  const double tol = plan.absolute_tolerance();
  chart.horizontal_band(plan.measured - tol, plan.measured + tol, colours::green);
  if (res.predict_sd) chart.band(xs, lo, hi, colours::blue);
  chart.polyline(xs, ys, colours::blue, 3);
  chart.horizontal(plan.measured, colours::green, 2);
  for (auto* run : shown) chart.marker(run->spec.x[j], response(*run, plan.response), colours::black, 4);
  chart.vertical(res.chosen[j], colours::red, 2);
  chart.title("Calibration curve: " + plan.response + " vs " + f.name);
  chart.labels(factor_label(f) + ", " + f.key, quantity_label(plan.response));
  std::vector<LegendEntry> legend = {{"model", colours::blue}, {"measured +- tolerance", colours::green},
                                                        {"calibrated " + f.name, colours::red}};
  if (!shown.empty()) legend.push_back({"simulated runs", colours::black});
  chart.legend(legend);
  const std::string file = "calibration_" + f.name + ".png";
  chart.save(dir + "/" + file);
  std::string caption = "Calibration curve of " + f.name + ": the model's " + plan.response + " along " + f.name;
  if (plan.factors.size() > 1) caption += " with the other factors at their calibrated values";
  if (res.predict_sd) caption += " (band: +-2 posterior sd)";
  return {file, caption + "; green: measured value and tolerance; red: calibrated value; dots: runs on this line."};
}

Figure predicted_vs_simulated(const CampaignPlan& plan, const CalibrationResult& res, const std::vector<RunRecord>& runs,
                              const std::string& dir) {
  Range r;
  std::vector<std::pair<double, double>> pts;
  for (const auto& run : runs) {
    Eigen::VectorXd c(run.spec.x.size());
    for (size_t m = 0; m < run.spec.x.size(); ++m) c[m] = coded(plan.factors[m], run.spec.x[m]);
    pts.push_back({response(run, plan.response), res.predict(c)});
    r.add(pts.back().first);
    r.add(pts.back().second);
  }
  for (const auto& v : res.verification) {
    r.add(response(v, plan.response));
    r.add(res.predicted);
  }
  r.pad(0.08);
  Chart chart(760, 700, r.lo, r.hi, r.lo, r.hi);
  chart.polyline({r.lo, r.hi}, {r.lo, r.hi}, colours::grey, 1);
  for (const auto& [s, p] : pts) chart.marker(s, p, colours::blue, 4);
  for (const auto& v : res.verification) chart.marker(response(v, plan.response), res.predicted, colours::red, 5);
  chart.title("Predicted vs simulated " + plan.response);
  chart.labels("simulated " + quantity_label(plan.response), "predicted " + quantity_label(plan.response));
  chart.legend({{"model runs", colours::blue}, {"verification", colours::red}});
  chart.save(dir + "/predicted_vs_simulated.png");
  return {"predicted_vs_simulated.png", "Predicted against simulated " + plan.response +
                                            " for the runs the model was fitted to (blue) and the verification runs (red)."};
}

Figure verification(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  Range r;
  const double tol = plan.absolute_tolerance();
  r.add(plan.measured - 2 * tol);
  r.add(plan.measured + 2 * tol);
  for (const auto& v : res.verification) r.add(response(v, plan.response));
  r.pad(0.1);
  const int n = int(res.verification.size());
  Chart chart(760, 520, 0.5, n + 0.5, r.lo, r.hi);
  chart.horizontal_band(plan.measured - tol, plan.measured + tol, colours::green);
  chart.horizontal(plan.measured, colours::green, 2);
  chart.horizontal(res.verification_mean, colours::red, 1);
  for (int i = 0; i < n; ++i) chart.marker(i + 1, response(res.verification[i], plan.response), colours::red, 5);
  chart.title("Verification runs at the calibrated point");
  chart.labels("run (its own packing seed)", quantity_label(plan.response));
  chart.legend({{"measured +- tolerance", colours::green}, {"runs and their mean", colours::red}});
  chart.save(dir + "/verification.png");
  return {"verification.png", "The verification runs (each with its own packing seed) against the measured value and its tolerance band."};
}

}  // namespace

std::vector<Figure> write_figures(const CampaignPlan& plan, const CalibrationResult& res, const std::vector<RunRecord>& runs,
                                  const std::string& dir) {
  std::vector<Figure> out;
  if (plan.factors.size() >= 2) {
    out.push_back(contour(plan, res, runs, dir));
    out.push_back(main_effects(plan, res, dir));
  }
  for (int j = 0; j < int(plan.factors.size()); ++j) out.push_back(calibration_curve(plan, res, runs, j, dir));
  out.push_back(predicted_vs_simulated(plan, res, runs, dir));
  if (!res.verification.empty()) out.push_back(verification(plan, res, dir));
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
  r.add(100 * plan.tolerance);
  r.pad(0.05);
  Chart chart(860, 540, 0.5, xs.size() + 0.5, 0, r.hi);
  chart.horizontal(100 * plan.tolerance, colours::green, 2);
  chart.vertical(loop.initial + 0.5, colours::grey, 1);
  chart.polyline(xs, best, colours::blue, 3);
  for (size_t i = 0; i < xs.size(); ++i) chart.marker(xs[i], each[i], colours::black, 4);
  chart.title("Adaptive loop: error of each run and best so far");
  chart.labels("simulation", "|simulated - measured| / measured (%)");
  chart.legend({{"best so far", colours::blue}, {"tolerance", colours::green}, {"each run", colours::black}});
  chart.save(dir + "/convergence.png");
  return {"convergence.png", "Relative error of each simulation of the loop (dots) and the best so far (blue); left of the grey "
                             "line the space-filling start, right of it the proposals; green: the tolerance."};
}

}  // namespace repose::calibrate
