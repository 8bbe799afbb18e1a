#include "diagnosis/plot_png.h"

#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace repose {

namespace {

class Canvas {
 public:
  Canvas(int w, int h) : w_(w), h_(h), px_(size_t(w) * h * 3, 255) {}
  void set(int x, int y, PlotColour c) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    size_t k = (size_t(y) * w_ + x) * 3;
    px_[k] = c[0];
    px_[k + 1] = c[1];
    px_[k + 2] = c[2];
  }
  void rect(int x0, int y0, int x1, int y1, PlotColour c) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) set(x, y, c);
  }
  void line(double x0, double y0, double x1, double y1, PlotColour c, int half = 0) {
    int n = int(std::ceil(2 * std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
    for (int i = 0; i <= n; ++i) {
      double t = double(i) / n;
      int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
      rect(x - half, y - half, x + half + 1, y + half + 1, c);
    }
  }
  // stb_easy_font quads are axis-aligned rectangles: fill each, scaled.
  void text(double x, double y, const std::string& s, PlotColour c, int scale = 1) {
    std::vector<char> buffer(64 * 1000);
    int quads = stb_easy_font_print(0, 0, const_cast<char*>(s.c_str()), nullptr, buffer.data(), int(buffer.size()));
    for (int q = 0; q < quads; ++q) {
      const float* v0 = reinterpret_cast<const float*>(buffer.data() + q * 64);
      const float* v2 = reinterpret_cast<const float*>(buffer.data() + q * 64 + 32);
      rect(int(x + v0[0] * scale), int(y + v0[1] * scale), int(x + v2[0] * scale), int(y + v2[1] * scale), c);
    }
  }
  static int text_width(const std::string& s, int scale = 1) {
    return stb_easy_font_width(const_cast<char*>(s.c_str())) * scale;
  }
  void save(const std::string& path) const {
    if (!stbi_write_png(path.c_str(), w_, h_, 3, px_.data(), w_ * 3))
      throw std::runtime_error(path + ": cannot write the PNG");
  }

 private:
  int w_, h_;
  std::vector<uint8_t> px_;
};

// "Nice" tick spacing: 1, 2 or 5 times a power of ten, about 5 ticks over the range.
double tick_step(double span) {
  double raw = span / 5, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::string label(double v, double step) {
  char buf[32];
  int decimals = std::max(0, int(-std::floor(std::log10(step) + 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 6), std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buf;
}

}  // namespace

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
  double px = 0.06 * (x1 - x0), py = 0.08 * (y1 - y0);
  x0 -= px; x1 += px; y0 -= py; y1 += py;

  Canvas c(width, height);
  const int left = 80, right = 20, top = 40, bottom = 50;
  int pw = width - left - right, ph = height - top - bottom;
  auto sx = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  auto sy = [&](double y) { return top + (y1 - y) / (y1 - y0) * ph; };
  const PlotColour black{0, 0, 0}, grey{200, 200, 200};

  double xs = tick_step(x1 - x0), ys = tick_step(y1 - y0);
  for (double t = std::ceil(x0 / xs) * xs; t <= x1; t += xs) {
    c.line(sx(t), top, sx(t), top + ph, grey);
    std::string l = label(t, xs);
    c.text(sx(t) - Canvas::text_width(l) / 2.0, top + ph + 6, l, black);
  }
  for (double t = std::ceil(y0 / ys) * ys; t <= y1; t += ys) {
    c.line(left, sy(t), left + pw, sy(t), grey);
    std::string l = label(t, ys);
    c.text(left - 6 - Canvas::text_width(l), sy(t) - 4, l, black);
  }
  if (plot.zero_line) c.line(left, sy(0), left + pw, sy(0), {120, 120, 120}, 0);
  if (plot.diagonal) c.line(sx(x0), sy(x0), sx(x1), sy(x1), {120, 120, 120}, 0);
  c.line(left, top, left, top + ph, black);
  c.line(left, top + ph, left + pw, top + ph, black);

  for (const auto& s : plot.series) {
    for (size_t k = 0; k < s.x.size(); ++k) {
      if (s.line && k > 0) c.line(sx(s.x[k - 1]), sy(s.y[k - 1]), sx(s.x[k]), sy(s.y[k]), s.colour, 1);
      if (k < s.error.size() && s.error[k] > 0)
        c.line(sx(s.x[k]), sy(s.y[k] - s.error[k]), sx(s.x[k]), sy(s.y[k] + s.error[k]), s.colour);
      if (s.points) c.rect(int(sx(s.x[k])) - 3, int(sy(s.y[k])) - 3, int(sx(s.x[k])) + 4, int(sy(s.y[k])) + 4, s.colour);
    }
  }
  // Title, axis labels, legend.
  c.text(left, 10, plot.title, black, 2);
  c.text(left + pw / 2.0 - Canvas::text_width(plot.x_label) / 2.0, height - 22, plot.x_label, black);
  c.text(6, top - 14, plot.y_label, black);
  int ly = top + 8;
  for (const auto& s : plot.series) {
    if (s.label.empty()) continue;
    int lx = left + pw - 10 - Canvas::text_width(s.label) - 24;
    c.rect(lx, ly, lx + 16, ly + 8, s.colour);
    c.text(lx + 22, ly, s.label, black);
    ly += 14;
  }
  c.save(path);
}

}  // namespace repose
