#include "diagnosis/plot_png.h"

#include <algorithm>

#include "plot/chart.h"

namespace repose {

void write_plot_png(const Plot& plot, const std::string& path, int width, int height) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& s : plot.series)
    for (size_t k = 0; k < s.x.size(); ++k) {
      double e = k < s.error.size() ? s.error[k] : 0;
      x0 = std::min(x0, s.x[k]);
      x1 = std::max(x1, s.x[k]);
      y0 = std::min(y0, s.y[k] - e);
      y1 = std::max(y1, s.y[k] + e);
    }
  if (x0 > x1) { x0 = 0; x1 = 1; y0 = 0; y1 = 1; }
  if (plot.zero_line) { y0 = std::min(y0, 0.0); y1 = std::max(y1, 0.0); }
  if (plot.diagonal) { x0 = y0 = std::min(x0, y0); x1 = y1 = std::max(x1, y1); }
  if (x1 - x0 <= 0) { x0 -= 0.5; x1 += 0.5; }
  if (y1 - y0 <= 0) { y0 -= 0.5; y1 += 0.5; }
  // A margin so that no point or error bar sits on the frame.
  double px = 0.06 * (x1 - x0), py = 0.08 * (y1 - y0);
  Chart chart(width, height, x0 - px, x1 + px, y0 - py, y1 + py);
  if (plot.zero_line) chart.horizontal(0, {120, 120, 120});
  if (plot.diagonal) chart.polyline({x0 - px, x1 + px}, {x0 - px, x1 + px}, {120, 120, 120});
  std::vector<LegendEntry> legend;
  if (plot.diagonal) legend.push_back({plot.diagonal_label, {120, 120, 120}, Mark::Line});
  for (const auto& s : plot.series) {
    for (size_t k = 0; k < s.x.size(); ++k) {
      if (k < s.error.size() && s.error[k] > 0) chart.error_bar(s.x[k], s.y[k] - s.error[k], s.y[k] + s.error[k], s.colour);
      if (s.points) chart.square(s.x[k], s.y[k], s.colour, 3);
    }
    if (s.line) chart.polyline(s.x, s.y, s.colour, 2);
    // The entry shows what the series draws: its line, else its squares.
    if (!s.label.empty()) legend.push_back({s.label, s.colour, s.line ? Mark::Line : Mark::Square});
  }
  chart.title(plot.title);
  chart.labels(plot.x_label, plot.y_label);
  if (!legend.empty()) chart.legend(legend);
  chart.save(path);
}

}  // namespace repose
