#include "stats/design_figures.h"

#include <algorithm>
#include <cmath>

#include "plot/chart.h"
#include "util/number_text.h"

namespace repose::stats {

namespace {

const Colour kRaises = colours::orange, kLowers = colours::blue;

std::string num(double v) { return format_g(v, 3); }

}  // namespace

void write_pareto_chart(const std::vector<Effect>& effects, int residual_df, double alpha,
                        const std::string& response, const std::string& path) {
  const int m = int(effects.size());
  double t_limit = t_value_limit(alpha, residual_df), bonferroni = bonferroni_limit(alpha, m, residual_df);
  double top = bonferroni;
  for (const Effect& e : effects) top = std::max(top, std::abs(e.t));
  // Room above the limits for the legend's four rows, so that it hides neither bars nor limits.
  Chart chart(900, 600, 0.3, m + 0.7, 0, 1.4 * top);
  bool raises = false, lowers = false;
  for (int i = 0; i < m; ++i) {
    const Effect& e = effects[size_t(i)];
    double x = i + 1, t = std::abs(e.t);
    Colour c = e.t >= 0 ? kRaises : kLowers;
    (e.t >= 0 ? raises : lowers) = true;
    chart.polygon({x - 0.35, x + 0.35, x + 0.35, x - 0.35}, {0, 0, t, t}, c, colours::black);
    chart.text_at(x - 0.3, t + 0.05 * top, e.term, colours::black);
  }
  chart.horizontal(t_limit, colours::black, 2);
  chart.horizontal(bonferroni, colours::red, 2);
  chart.title("Pareto chart of standardised effects on " + response);
  chart.subtitle("t = coefficient / standard error, " + std::to_string(residual_df) + " residual df, alpha " + num(alpha));
  chart.labels("rank", "|t| of the effect");
  std::vector<LegendEntry> legend;
  if (raises) legend.push_back({"raises " + response, kRaises, Mark::Bar});
  if (lowers) legend.push_back({"lowers " + response, kLowers, Mark::Bar});
  legend.push_back({"t-value limit " + num(t_limit), colours::black, Mark::Line});
  legend.push_back({"Bonferroni limit " + num(bonferroni), colours::red, Mark::Line});
  chart.legend(legend);
  chart.save(path);
}

void write_half_normal_plot(const std::vector<Effect>& effects, const std::string& response, const std::string& path) {
  std::vector<double> size;
  for (const Effect& e : effects) size.push_back(std::abs(e.effect));
  std::vector<size_t> order(size.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return size[a] < size[b]; });
  std::vector<double> q = half_normal_quantiles(int(size.size()));
  // The noise line: |effect| = s q through the origin, least squares over the smaller half.
  size_t half = std::max<size_t>(1, (size.size() + 1) / 2);
  double sq = 0, qq = 0;
  for (size_t k = 0; k < half; ++k) sq += size[order[k]] * q[k], qq += q[k] * q[k];
  double s = qq > 0 ? sq / qq : 0;
  double largest = size.empty() ? 1 : size[order.back()], q_top = q.empty() ? 1 : q.back();
  Chart chart(900, 600, 0, 1.25 * largest, 0, 1.1 * q_top);
  chart.polyline({0, s * 1.1 * q_top}, {0, 1.1 * q_top}, colours::grey, 2);
  bool raises = false, lowers = false;
  for (size_t k = 0; k < order.size(); ++k) {
    const Effect& e = effects[order[k]];
    Colour c = e.effect >= 0 ? kRaises : kLowers;
    (e.effect >= 0 ? raises : lowers) = true;
    chart.square(size[order[k]], q[k], c, 4);
    chart.text_at(size[order[k]], q[k], e.term, colours::black);
  }
  chart.title("Half-normal plot of the effects on " + response);
  chart.labels("|effect| (change of " + response + " from -1 to +1)", "half-normal quantile");
  std::vector<LegendEntry> legend;
  if (raises) legend.push_back({"raises " + response, kRaises, Mark::Square});
  if (lowers) legend.push_back({"lowers " + response, kLowers, Mark::Square});
  legend.push_back({"noise: line through the smaller half", colours::grey, Mark::Line});
  chart.legend(legend);
  chart.save(path);
}

void write_steepest_ascent_plot(const std::vector<PathPoint>& path, double target, const std::string& response,
                                const std::string& png) {
  double lo = target, hi = target, s0 = 0, s1 = 1;
  std::vector<double> x, y;
  for (const PathPoint& p : path) {
    lo = std::min(lo, p.response - p.se);
    hi = std::max(hi, p.response + p.se);
    x.push_back(p.step);
    y.push_back(p.response);
  }
  if (!x.empty()) s0 = *std::min_element(x.begin(), x.end()), s1 = *std::max_element(x.begin(), x.end());
  double pad_x = 0.08 * std::max(1.0, s1 - s0), pad_y = 0.1 * std::max(hi - lo, 1e-12);
  Chart chart(900, 600, s0 - pad_x, s1 + pad_x, lo - pad_y, hi + pad_y);
  chart.horizontal(target, colours::red, 2);
  chart.polyline(x, y, colours::blue, 2);
  for (const PathPoint& p : path) {
    if (p.se > 0) chart.error_bar(p.step, p.response - p.se, p.response + p.se, colours::blue);
    chart.square(p.step, p.response, colours::blue, 4);
  }
  chart.title("Steepest-ascent path: " + response + " at each step");
  chart.labels("step along the path", response);
  chart.legend({{response + " (bars: standard error)", colours::blue, Mark::Square},
                {"target " + num(target), colours::red, Mark::Line}});
  chart.save(png);
}

namespace {

// Ten bands from blue (low) to red (high), so that every colour of the legend is one the surface has.
Colour band_colour(double t) {
  int band = std::clamp(int(t * 10), 0, 9);
  double u = (band + 0.5) / 10;
  return {uint8_t(60 + 190 * u), uint8_t(110 + 80 * (1 - std::abs(2 * u - 1))), uint8_t(230 - 190 * u)};
}

// The view: u, v, w in [0, 1] (the two factors and the height) to the picture's plane, seen from
// above the corner u = v = 0.
constexpr double kCos30 = 0.86602540378, kSin30 = 0.5, kHeight = 0.9;
double view_x(double u, double v) { return (u - v) * kCos30; }
double view_y(double u, double v, double w) { return (u + v) * kSin30 + kHeight * w; }

// About 4 round ticks within [lo, hi], and where each sits between them (0 .. 1).
std::vector<double> axis_ticks(double lo, double hi, std::vector<double>& at) {
  std::vector<double> t = nice_ticks(lo, hi, 4);
  at.clear();
  for (double v : t) at.push_back((v - lo) / (hi - lo));
  return t;
}

// The width of a tick label in the picture's units (stb_easy_font at the chart's tick size).
double label_width(const std::string& s) { return 0.043 * double(s.size()); }

}  // namespace

void write_surface_3d(const SurfacePicture& s, const std::string& path) {
  constexpr int kGrid = 32;
  double z0 = INFINITY, z1 = -INFINITY;
  std::vector<double> z((kGrid + 1) * (kGrid + 1));
  auto at = [&](int i, int j) -> double& { return z[size_t(i) * (kGrid + 1) + j]; };
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; j <= kGrid; ++j) {
      at(i, j) = s.f(s.a0 + (s.a1 - s.a0) * i / kGrid, s.b0 + (s.b1 - s.b0) * j / kGrid);
      z0 = std::min(z0, at(i, j));
      z1 = std::max(z1, at(i, j));
    }
  for (const auto& r : s.runs) z0 = std::min(z0, r[2]), z1 = std::max(z1, r[2]);
  if (!(z1 > z0)) z1 = z0 + 1;
  auto w = [&](double v) { return (v - z0) / (z1 - z0); };
  Chart chart(900, 700, -kCos30 - 0.45, kCos30 + 0.45, -0.3, 1 + kHeight + 0.2);
  // The floor's outline and the vertical axis at the left corner, behind the surface.
  chart.polyline({view_x(0, 0), view_x(1, 0), view_x(1, 1), view_x(0, 1), view_x(0, 0)},
                 {view_y(0, 0, 0), view_y(1, 0, 0), view_y(1, 1, 0), view_y(0, 1, 0), view_y(0, 0, 0)}, colours::grey);
  chart.polyline({view_x(0, 1), view_x(0, 1)}, {view_y(0, 1, 0), view_y(0, 1, 1)}, colours::black);
  // Facets from the back (large u + v) to the front, each over what is behind it.
  double highest = -INFINITY;  // the highest facet's height (its colour names the model in the legend)
  for (int d = 2 * kGrid - 2; d >= 0; --d)
    for (int i = 0; i < kGrid; ++i) {
      int j = d - i;
      if (j < 0 || j >= kGrid) continue;
      double u0 = double(i) / kGrid, u1 = double(i + 1) / kGrid, v0 = double(j) / kGrid, v1 = double(j + 1) / kGrid;
      double mean = 0.25 * (at(i, j) + at(i + 1, j) + at(i + 1, j + 1) + at(i, j + 1));
      highest = std::max(highest, mean);
      chart.polygon({view_x(u0, v0), view_x(u1, v0), view_x(u1, v1), view_x(u0, v1)},
                    {view_y(u0, v0, w(at(i, j))), view_y(u1, v0, w(at(i + 1, j))), view_y(u1, v1, w(at(i + 1, j + 1))),
                     view_y(u0, v1, w(at(i, j + 1)))},
                    band_colour(w(mean)), {110, 110, 110});
    }
  for (const auto& r : s.runs) {
    double u = (r[0] - s.a0) / (s.a1 - s.a0), v = (r[1] - s.b0) / (s.b1 - s.b0);
    chart.marker(view_x(u, v), view_y(u, v, w(r[2])), colours::black, 5);
  }
  // Ticks: a along the front right edge (labels to its right), b along the front left edge
  // (labels to its left), z up the left corner (labels left of it).
  std::vector<double> a_at, b_at, z_at;
  std::vector<std::string> a_ticks = tick_labels(axis_ticks(s.a0, s.a1, a_at)),
                           b_ticks = tick_labels(axis_ticks(s.b0, s.b1, b_at)), z_ticks = tick_labels(axis_ticks(z0, z1, z_at));
  for (size_t k = 0; k < a_at.size(); ++k) {
    double t = a_at[k];
    chart.polyline({view_x(t, 0), view_x(t, 0) + 0.03}, {view_y(t, 0, 0), view_y(t, 0, 0) - 0.017}, colours::black);
    chart.text_at(view_x(t, 0) + 0.03, view_y(t, 0, 0) - 0.05, a_ticks[k], colours::black);
  }
  for (size_t k = 0; k < b_at.size(); ++k) {
    double t = b_at[k];
    chart.polyline({view_x(0, t), view_x(0, t) - 0.03}, {view_y(0, t, 0), view_y(0, t, 0) - 0.017}, colours::black);
    chart.text_at(view_x(0, t) - 0.06 - label_width(b_ticks[k]), view_y(0, t, 0) - 0.05, b_ticks[k], colours::black);
  }
  for (size_t k = 0; k < z_at.size(); ++k) {
    double t = z_at[k];
    chart.polyline({view_x(0, 1), view_x(0, 1) - 0.03}, {view_y(0, 1, t), view_y(0, 1, t)}, colours::black);
    chart.text_at(view_x(0, 1) - 0.08 - label_width(z_ticks[k]), view_y(0, 1, t) + 0.03, z_ticks[k], colours::black);
  }
  chart.text_at(view_x(0.5, 0) + 0.2, view_y(0.5, 0, 0) - 0.16, s.a_label, colours::black);
  chart.text_at(view_x(0, 0.5) - 0.2 - label_width(s.b_label), view_y(0, 0.5, 0) - 0.16, s.b_label, colours::black);
  chart.text_at(view_x(0, 1) - 0.2, view_y(0, 1, 1) + 0.12, s.z_label, colours::black);
  chart.hide_axes(a_ticks, b_ticks, s.z_label, z_ticks);
  chart.title(s.title);
  chart.labels(s.a_label, s.b_label);
  std::vector<LegendEntry> legend = {{"model (red high, blue low)", band_colour(w(highest)), Mark::Bar}};
  if (!s.runs.empty()) legend.push_back({"runs", colours::black, Mark::Dot});
  chart.legend(legend);
  chart.save(path);
}

}  // namespace repose::stats
