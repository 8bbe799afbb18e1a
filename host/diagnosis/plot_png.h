// Small x-y plots as PNG for the diagnosis report: points with error bars, lines, a legend,
// axis ticks and labels, drawn by the shared chart (plot/chart.h).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace repose {

using PlotColour = std::array<uint8_t, 3>;  // the chart's Colour

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::vector<double> error;  // half-height of an error bar per point (empty: none)
  PlotColour colour{0, 0, 0};
  bool line = false;          // join the points
  bool points = true;
};

struct Plot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  bool zero_line = false;     // a horizontal line at y = 0
  bool diagonal = false;      // the line y = x (measured vs simulated), with this legend entry
  std::string diagonal_label = "y = x";
};

// Throws std::runtime_error naming the path when it cannot write.
void write_plot_png(const Plot& plot, const std::string& path, int width = 860, int height = 540);

}  // namespace repose
