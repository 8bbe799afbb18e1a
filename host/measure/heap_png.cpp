#include "measure/heap_png.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "plot/chart.h"

namespace repose {

namespace {

std::string slope_words(const char* side, const SlopeFit& fit) {
  char text[64];
  if (fit.valid) std::snprintf(text, sizeof text, "%s %.2f deg", side, fit.angle_deg);
  else std::snprintf(text, sizeof text, "%s: no slope", side);
  return text;
}

// "this view: left 15.20 deg, right 15.91 deg" over the slopes that count.
std::string view_words(const HeapAngle& m, const HeapPictureCaption& caption) {
  std::string words;
  if (caption.left) words += slope_words("left", m.left);
  if (caption.right) words += (words.empty() ? "" : ", ") + slope_words("right", m.right);
  return "this view: " + words;
}

}  // namespace

HeapPictureCaption front_view_caption(const HeapAngle& m) {
  return {m.mean_deg, "the mean of both slopes", true, true};
}

HeapPictureCaption slope_caption(const HeapAngle& m, const std::string& side) {
  if (side == "both") return front_view_caption(m);
  const SlopeFit& fit = side == "left" ? m.left : m.right;
  return {fit.valid ? fit.angle_deg : std::numeric_limits<double>::quiet_NaN(), "the " + side + " slope",
          side == "left", side == "right"};
}

void write_heap_angle_png(const std::string& path, const HeapAngle& m, const std::string& horizontal,
                          const HeapPictureCaption& caption) {
  const BinaryImage& image = m.image;
  const double u0 = image.origin_u, u1 = u0 + image.width * image.pixel;
  const double z0 = image.origin_z, z1 = z0 + image.height * image.pixel;
  // Room above the heap for the legend, a little beside it; a heap taller than wide (what stays in
  // a drained box) is drawn in a picture as wide as the chart's 1400 x 1000, so its title fits.
  const double margin = 0.03 * (u1 - u0);
  // A heap far wider than tall (grains that ran out into a low mound) keeps its equal scale, so
  // its slopes look as steep as they are, under room enough for readable z ticks and the legend:
  // the picture at least a quarter as tall as wide.
  const double top = std::max(z1 + 0.3 * (z1 - z0), z0 + 0.25 * ((u1 - u0) + 2 * margin));
  const double widen = std::max(0.0, 0.5 * (1.4 * (top - z0) - (u1 - u0)) - margin);
  Chart chart = Chart::equal_scale(1400, 1000, u0 - margin - widen, u1 + margin + widen, z0, top);
  // The silhouette, then its top outline, the floor, the fitted lines and the points they used.
  // Columns the options hid (an opaque box's front wall) are drawn darker: not measured.
  const Colour hidden{150, 150, 165};
  auto is_hidden = [&](int c) { return m.visible_from && image.column_centre(c) < *m.visible_from; };
  chart.raster(image.width, image.height, u0, z0, image.pixel, [&](int c, int r) -> std::optional<Colour> {
    if (image.at(c, r)) return is_hidden(c) ? hidden : Colour{205, 205, 205};
    return std::nullopt;
  });
  std::vector<double> outline_u, outline_z;
  for (int c = 0; c < image.width; ++c)
    if (m.profile[size_t(c)] >= 0) {
      outline_u.push_back(image.column_centre(c));
      outline_z.push_back(image.row_top(m.profile[size_t(c)]));
    }
  std::vector<LegendEntry> legend{{"outline", colours::black}};
  chart.polyline(outline_u, outline_z, colours::black, 1);
  chart.horizontal(m.floor_z, colours::green, 2);
  // Each fitted line that counts, from the floor to the crest height, like the studies' figures
  // (clipped to the picture).
  auto draw_fit = [&](const SlopeFit& fit, bool counts, Colour colour, const char* label) {
    if (!counts || !fit.valid || fit.line.slope == 0) return false;
    const double top_z = m.floor_z + m.heap_height;
    const double u_floor = (m.floor_z - fit.line.intercept) / fit.line.slope;
    const double u_top = (top_z - fit.line.intercept) / fit.line.slope;
    chart.polyline({u_floor, u_top}, {m.floor_z, top_z}, colour, 3);
    legend.push_back({label, colour});
    return true;
  };
  const bool left = draw_fit(m.left, caption.left, colours::red, "left fit");
  const bool right = draw_fit(m.right, caption.right, colours::blue, "right fit");
  bool points = false;
  for (int c = 0; c < image.width; ++c) {
    const uint8_t side = m.fitted_columns[size_t(c)];
    if (m.profile[size_t(c)] < 0 || !((side == 1 && left) || (side == 2 && right))) continue;
    chart.square(image.column_centre(c), image.row_top(m.profile[size_t(c)]), colours::orange, 1);
    points = true;
  }
  if (points) legend.push_back({"fitted points", colours::orange, Mark::Square});
  legend.push_back({"floor", colours::green});
  if (m.visible_from) legend.push_back({"hidden (not measured)", hidden, Mark::Square});

  const bool measured = std::isfinite(caption.angle_deg);
  char title[200];
  if (measured)
    std::snprintf(title, sizeof title, "Angle of repose %.2f deg (%s)", caption.angle_deg, caption.measured_as.c_str());
  else
    std::snprintf(title, sizeof title, "Angle of repose: no slope measured");
  chart.title(caption.warning.empty() ? std::string(title) : std::string(title) + ", " + caption.warning);
  char subtitle[240];
  std::snprintf(subtitle, sizeof subtitle, "%s; heap %.3g m high%s", view_words(m, caption).c_str(), m.heap_height,
                points ? "; orange: the outline points fitted (the band of the height)" : "");
  chart.subtitle(subtitle);
  chart.labels(horizontal + " (m)", "z (m)");
  chart.legend(legend);
  chart.save(path);
}

}  // namespace repose
