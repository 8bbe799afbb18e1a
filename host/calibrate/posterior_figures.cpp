// posterior.png: what the measurement says about the parameters (report_figures.h).
#include <algorithm>
#include <cmath>
#include <numeric>

#include "calibrate/report_figures.h"
#include "plot/chart.h"
#include "util/units.h"

namespace repose::calibrate {

namespace {

// The marginal over two free factors on a square grid of bins (the posterior's own cells when it
// is a grid), and the mass above which a bin lies in the marginal's 90 % region.
struct Marginal2 {
  int n = 0;
  std::vector<double> mass;  // n x n, a along the row
  double threshold = 0;
  double at(double ca, double cb) const {
    const int i = std::clamp(int((ca + 1) / 2 * n), 0, n - 1), j = std::clamp(int((cb + 1) / 2 * n), 0, n - 1);
    return mass[size_t(j) * size_t(n) + size_t(i)];
  }
};

Marginal2 marginal2(const Posterior& post, int a, int b) {
  Marginal2 m;
  m.n = post.per_axis.empty() ? 60 : post.per_axis[0];
  m.mass.assign(size_t(m.n) * size_t(m.n), 0.0);
  for (size_t k = 0; k < post.nodes.size(); ++k) {
    const int i = std::clamp(int((post.nodes[k][a] + 1) / 2 * m.n), 0, m.n - 1);
    const int j = std::clamp(int((post.nodes[k][b] + 1) / 2 * m.n), 0, m.n - 1);
    m.mass[size_t(j) * size_t(m.n) + size_t(i)] += post.mass[k];
  }
  std::vector<double> sorted = m.mass;
  std::sort(sorted.begin(), sorted.end(), std::greater<>());
  double cum = 0;
  for (double v : sorted) {
    cum += v;
    m.threshold = v;
    if (cum >= post.region_mass) break;
  }
  return m;
}

Figure posterior_2d(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  const Posterior& post = res.posterior;
  const int a = post.free[0], b = post.free[1];
  const PlanFactor &fa = plan.factors[size_t(a)], &fb = plan.factors[size_t(b)];
  const Marginal2 m = marginal2(post, a, b);
  // The runs beyond the box (axial points) stay in view; the prior, and so the posterior, is zero there.
  const double e = std::max(1.0, res.coded_extent) * 1.04;
  Chart chart(900, 720, fa.to_actual(-e), fa.to_actual(e), fb.to_actual(-e), fb.to_actual(e), true);
  auto density = [&](double x, double y) {
    const double ca = fa.to_coded(x), cb = fb.to_coded(y);
    return std::abs(ca) > 1 || std::abs(cb) > 1 ? 0.0 : m.at(ca, cb);
  };
  // The region's edge: halfway between the last bin inside and the next one out.
  chart.response_map(density, {}, {m.threshold * 0.999}, "posterior mass per cell");
  // The ridge through the posterior mean, in actual units.
  const Eigen::VectorXd& d = post.ridge;
  const double ma = post.marginal[size_t(a)].mean, mb = post.marginal[size_t(b)].mean;
  std::vector<double> rx, ry;
  for (int t = -30; t <= 30; ++t) {
    rx.push_back(fa.to_actual(ma + 0.1 * t * d[a]));
    ry.push_back(fb.to_actual(mb + 0.1 * t * d[b]));
  }
  std::vector<LegendEntry> legend = {{"90 % region", colours::black, Mark::Line}};
  if (std::abs(d[a]) + std::abs(d[b]) > 1e-9) {
    chart.polyline(rx, ry, colours::orange, 3);
    legend.push_back({"ridge", colours::orange, Mark::Line});
  }
  for (const auto& run : res.primary().runs) chart.marker(run.spec.x[size_t(a)], run.spec.x[size_t(b)], colours::black, 5);
  chart.cross(res.chosen[size_t(a)], res.chosen[size_t(b)], colours::red, 9);
  legend.push_back({"runs", colours::black, Mark::Dot});
  legend.push_back({"chosen", colours::red, Mark::Cross});
  chart.title("Posterior of " + fa.name + " and " + fb.name + " given the measured value");
  chart.labels(factor_label(fa), factor_label(fb));
  chart.legend_above(legend);
  chart.save(dir + "/posterior.png");
  std::string others = plan.factors.size() > 2 ? " (the other factors integrated out)" : "";
  return {"posterior.png", "Posterior of " + fa.name + " and " + fb.name + others +
                               ": colour the mass per cell, black the edge of its 90 % credible region, orange the ridge "
                               "(the direction the data leave most free), dots the runs, red cross the chosen point. " +
                               res.ridge_text};
}

Figure posterior_1d(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  const Posterior& post = res.posterior;
  const int a = post.free[0];
  const PlanFactor& f = plan.factors[size_t(a)];
  const int n = post.per_axis.empty() ? 200 : post.per_axis[0];
  std::vector<double> xs, dens(size_t(n), 0.0);
  for (size_t k = 0; k < post.nodes.size(); ++k)
    dens[size_t(std::clamp(int((post.nodes[k][a] + 1) / 2 * n), 0, n - 1))] += post.mass[k];
  const double width = (f.high - f.low) / n;
  double top = 0;
  for (int i = 0; i < n; ++i) {
    xs.push_back(f.low + (i + 0.5) * width);
    dens[size_t(i)] /= width;
    top = std::max(top, dens[size_t(i)]);
  }
  const ParameterEstimate& p = res.parameters[size_t(a)];
  Chart chart(860, 560, f.low, f.high, 0, top * 1.1);
  std::vector<double> bx, blo, bhi;
  for (int i = 0; i < n; ++i)
    if (xs[size_t(i)] >= p.low && xs[size_t(i)] <= p.high) {
      bx.push_back(xs[size_t(i)]);
      blo.push_back(0);
      bhi.push_back(dens[size_t(i)]);
    }
  if (bx.size() >= 2) chart.band(bx, blo, bhi, colours::blue);
  chart.polyline(xs, dens, colours::blue, 3);
  chart.vertical(res.chosen[size_t(a)], colours::red, 2);
  chart.title("Posterior of " + f.name + " given the measured value");
  chart.labels(factor_label(f), "posterior density (per unit of " + f.name + ")");
  chart.legend({{"posterior density", colours::blue, Mark::Line}, {"90 % credible interval", colours::blue, Mark::Band},
                {"chosen " + f.name, colours::red, Mark::Line}});
  chart.save(dir + "/posterior.png");
  return {"posterior.png", "Posterior density of " + f.name + " (flat prior over its range) given the measured value, the lab's "
                           "standard error and the model's uncertainty; shaded its 90 % credible interval, red the chosen value."};
}

}  // namespace

std::vector<Figure> posterior_figures(const CampaignPlan& plan, const CalibrationResult& res, const std::string& dir) {
  if (!res.posterior.computed) return {};
  if (res.posterior.free.size() >= 2) return {posterior_2d(plan, res, dir)};
  return {posterior_1d(plan, res, dir)};
}

}  // namespace repose::calibrate
