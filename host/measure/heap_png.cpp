#include "measure/heap_png.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "plot/chart.h"

namespace repose {

namespace {

std::string slope_words(const char* side, const SlopeFit& fit) {
  char text[64];
  if (fit.valid) std::snprintf(text, sizeof text, "%s %.2f deg", side, fit.angle_deg);
  else std::snprintf(text, sizeof text, "%s: no slope", side);
  return text;
}

}  // namespace

void write_heap_angle_png(const std::string& path, const HeapAngle& m, const std::string& horizontal) {
  const BinaryImage& image = m.image;
  const double u0 = image.origin_u, u1 = u0 + image.width * image.pixel;
  const double z0 = image.origin_z, z1 = z0 + image.height * image.pixel;
  // Room above the heap for the legend, a little beside it; a heap taller than wide (what stays in
  // a drained box) is drawn in a picture as wide as the chart's 1400 x 1000, so its title fits.
  const double margin = 0.03 * (u1 - u0);
  const double top = z1 + 0.3 * (z1 - z0);
  const double widen = std::max(0.0, 0.5 * (1.4 * (top - z0) - (u1 - u0)) - margin);
  Chart chart = Chart::equal_scale(1400, 1000, u0 - margin - widen, u1 + margin + widen, z0, top);
  // The silhouette, then its top outline, the floor, the fitted lines and the points they used.
  chart.raster(image.width, image.height, u0, z0, image.pixel, [&](int c, int r) -> std::optional<Colour> {
    if (image.at(c, r)) return Colour{205, 205, 205};
    return std::nullopt;
  });
  std::vector<double> outline_u, outline_z;
  for (int c = 0; c < image.width; ++c)
    if (m.profile[size_t(c)] >= 0) {
      outline_u.push_back(image.column_centre(c));
      outline_z.push_back(image.row_top(m.profile[size_t(c)]));
    }
  chart.polyline(outline_u, outline_z, colours::black, 1);
  chart.horizontal(m.floor_z, colours::green, 2);
  // Each fitted line from the floor to the crest height, like the studies' figures (clipped to
  // the picture).
  auto draw_fit = [&](const SlopeFit& fit, Colour colour) {
    if (!fit.valid || fit.line.slope == 0) return;
    const double top_z = m.floor_z + m.heap_height;
    const double u_floor = (m.floor_z - fit.line.intercept) / fit.line.slope;
    const double u_top = (top_z - fit.line.intercept) / fit.line.slope;
    chart.polyline({u_floor, u_top}, {m.floor_z, top_z}, colour, 3);
  };
  draw_fit(m.left, colours::red);
  draw_fit(m.right, colours::blue);
  for (int c = 0; c < image.width; ++c)
    if (m.fitted_columns[size_t(c)] && m.profile[size_t(c)] >= 0)
      chart.square(image.column_centre(c), image.row_top(m.profile[size_t(c)]), colours::orange, 1);

  char title[160];
  if (std::isfinite(m.mean_deg))
    std::snprintf(title, sizeof title, "Angle of repose %.2f deg (%s, %s)", m.mean_deg,
                  slope_words("left", m.left).c_str(), slope_words("right", m.right).c_str());
  else
    std::snprintf(title, sizeof title, "Angle of repose: no slope measured");
  chart.title(title);
  char subtitle[160];
  std::snprintf(subtitle, sizeof subtitle, "heap %.3g m high; orange: the outline points fitted (the band of the height)%s",
                m.heap_height, std::isfinite(m.mean_deg) ? "" : "; neither side gave a slope");
  chart.subtitle(subtitle);
  chart.labels(horizontal + " (m)", "z (m)");
  chart.legend({{"outline", colours::black}, {"left fit", colours::red}, {"right fit", colours::blue},
                {"fitted points", colours::orange}, {"floor", colours::green}});
  chart.save(path);
}

}  // namespace repose
