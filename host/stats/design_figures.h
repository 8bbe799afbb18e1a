// Design-Expert's pictures of a design and its fit, as PNG (plot/chart.h), each with a record its
// tests read back: the Pareto chart of standardised effects and the half-normal plot of a
// screening (Plackett-Burman, two-level factorial), the response along a steepest-ascent path, and
// a 3D picture of a fitted response surface over two factors.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "stats/effects.h"

namespace repose::stats {

// Bars of |t| by rank (orange: the effect raises the response, blue: lowers it), each named, with
// the t-value limit and the Bonferroni limit at `alpha` (residual df).
void write_pareto_chart(const std::vector<Effect>& effects, int residual_df, double alpha,
                        const std::string& response, const std::string& path);

// |effect| against its half-normal quantile, each named, with the line through the origin fitted
// to the smaller half (the effects that are noise): real effects stand off it to the right.
void write_half_normal_plot(const std::vector<Effect>& effects, const std::string& response, const std::string& path);

// The response at each step of a steepest-ascent (or descent) path, with its standard error where
// the steps were replicated, and the target it seeks.
struct PathPoint {
  double step = 0;
  double response = 0;
  double se = 0;  // 0: one run
};
void write_steepest_ascent_plot(const std::vector<PathPoint>& path, double target, const std::string& response,
                                const std::string& png);

// A fitted surface z = f(a, b) over [a0, a1] x [b0, b1] seen from above a corner, coloured by
// height, with its three axes ticked and the runs as dots.
struct SurfacePicture {
  std::function<double(double, double)> f;
  double a0 = -1, a1 = 1, b0 = -1, b1 = 1;
  std::string a_label, b_label, z_label, title;
  std::vector<std::array<double, 3>> runs;  // (a, b, response) of each run
};
void write_surface_3d(const SurfacePicture& s, const std::string& path);

}  // namespace repose::stats
