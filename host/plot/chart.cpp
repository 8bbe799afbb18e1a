#include "plot/chart.h"

#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/number_text.h"

namespace repose {

const std::vector<Colour>& colours::series() {
  static const std::vector<Colour> s = {blue, red, green, orange, purple, {0, 150, 160}, {120, 80, 40}, grey};
  return s;
}

namespace {

// Text sizes (stb_easy_font's glyphs are 7 pixels tall at scale 1).
constexpr double kTickText = 2.0, kLabelText = 2.2, kTitleText = 2.6;

// Ticks at 1, 2 or 5 times a power of ten, about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 6) {
  double span = hi - lo, raw = span / target;
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> t;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step) t.push_back(std::abs(v) < 1e-12 * span ? 0 : v);
  return t;
}

std::string tick_text(double v) { return format_g(v, 4); }

Colour heat(double t) {  // 0 blue .. 0.5 white .. 1 red, pale so lines stay visible
  t = std::clamp(t, 0.0, 1.0);
  auto mix = [](double a, double b, double u) { return uint8_t(std::lround(a + (b - a) * u)); };
  if (t < 0.5) return {mix(120, 250, t * 2), mix(160, 250, t * 2), mix(235, 250, t * 2)};
  return {mix(250, 235, (t - 0.5) * 2), mix(250, 140, (t - 0.5) * 2), mix(250, 120, (t - 0.5) * 2)};
}

void widen(double& a, double& b) {
  if (!(b > a)) {
    double pad = a == 0 ? 1 : 0.05 * std::abs(a);
    a -= pad;
    b += pad;
  }
}

}  // namespace

Chart::Chart(int width, int height, double x0, double x1, double y0, double y1, bool colour_bar)
    : w_(width), h_(height), x0_(x0), x1_(x1), y0_(y0), y1_(y1), colour_bar_(colour_bar),
      pixels_(size_t(width) * height * 3, 255) {
  widen(x0_, x1_);
  widen(y0_, y1_);
  if (colour_bar_) right_ += 130;
}

Chart Chart::equal_scale(int max_width, int max_height, double x0, double x1, double y0, double y1) {
  widen(x0, x1);
  widen(y0, y1);
  Chart probe(max_width, max_height, x0, x1, y0, y1);
  const int across = probe.left_ + probe.right_, down = probe.top_ + probe.bottom_;
  const double aspect = (y1 - y0) / (x1 - x0);
  double plot_width = max_width - across, plot_height = plot_width * aspect;
  if (plot_height > max_height - down) {
    plot_height = max_height - down;
    plot_width = plot_height / aspect;
  }
  return Chart(int(std::lround(plot_width)) + across, int(std::lround(plot_height)) + down, x0, x1, y0, y1);
}

void Chart::title(const std::string& t) { title_ = t; }
void Chart::subtitle(const std::string& t) { subtitle_ = t; }
void Chart::labels(const std::string& x, const std::string& y) {
  x_label_ = x;
  y_label_ = y;
}

double Chart::px(double x) const { return left_ + (x - x0_) / (x1_ - x0_) * (w_ - left_ - right_); }
double Chart::py(double y) const { return (h_ - bottom_) - (y - y0_) / (y1_ - y0_) * (h_ - top_ - bottom_); }

std::array<int, 4> Chart::plot_area() const {
  return {int(std::lround(px(x0_))), int(std::lround(py(y1_))), int(std::lround(px(x1_))), int(std::lround(py(y0_)))};
}

Colour Chart::pixel(int c, int r) const {
  size_t k = (size_t(r) * w_ + c) * 3;
  return {pixels_[k], pixels_[k + 1], pixels_[k + 2]};
}

void Chart::set(int c, int r, Colour colour) {
  if (c < 0 || r < 0 || c >= w_ || r >= h_) return;
  size_t k = (size_t(r) * w_ + c) * 3;
  std::copy(colour.begin(), colour.end(), pixels_.begin() + long(k));
}

void Chart::blend(int c, int r, Colour colour, double alpha) {
  if (c < 0 || r < 0 || c >= w_ || r >= h_) return;
  size_t k = (size_t(r) * w_ + c) * 3;
  for (int i = 0; i < 3; ++i) pixels_[k + i] = uint8_t(std::lround(pixels_[k + i] * (1 - alpha) + colour[i] * alpha));
}

void Chart::segment(double c0, double r0, double c1, double r1, Colour colour, int thickness) {
  const double steps = std::ceil(2.0 * std::max(std::abs(c1 - c0), std::abs(r1 - r0))) + 1;
  const int lo = -(thickness - 1) / 2, hi = thickness / 2;
  for (int i = 0; i <= int(steps); ++i) {
    double t = i / steps;
    int c = int(std::lround(c0 + t * (c1 - c0))), r = int(std::lround(r0 + t * (r1 - r0)));
    for (int dc = lo; dc <= hi; ++dc)
      for (int dr = lo; dr <= hi; ++dr) set(c + dc, r + dr, colour);
  }
}

// Liang-Barsky: the part of the segment inside the plot area (nothing when it misses it).
void Chart::clipped_segment(double c0, double r0, double c1, double r1, Colour colour, int thickness) {
  auto [left, top, right, bottom] = plot_area();
  double t0 = 0, t1 = 1, dc = c1 - c0, dr = r1 - r0;
  for (auto [p, q] : {std::pair{-dc, c0 - left}, {dc, right - c0}, {-dr, r0 - top}, {dr, bottom - r0}}) {
    if (p == 0) {
      if (q < 0) return;
      continue;
    }
    double t = q / p;
    if (p < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (t0 > t1) return;
  segment(c0 + t0 * dc, r0 + t0 * dr, c0 + t1 * dc, r0 + t1 * dr, colour, thickness);
}

// stb_easy_font gives axis-aligned quads; each is filled, scaled, and turned a quarter left
// for text that reads upwards (c, r is then the text's lower left corner).
void Chart::text(double c, double r, const std::string& s, Colour colour, double scale, bool upwards) {
  static char buffer[99999];
  int quads = stb_easy_font_print(0, 0, const_cast<char*>(s.c_str()), nullptr, buffer, sizeof buffer);
  const float* v = reinterpret_cast<const float*>(buffer);
  for (int q = 0; q < quads; ++q) {
    const float* a = v + q * 16;  // 4 vertices of (x, y, z, colour) = 16 bytes each
    double qx0 = a[0] * scale, qy0 = a[1] * scale, qx1 = a[8] * scale, qy1 = a[9] * scale;
    for (int i = int(std::floor(qy0)); i < int(std::floor(qy1)); ++i)
      for (int j = int(std::floor(qx0)); j < int(std::floor(qx1)); ++j)
        if (upwards) set(int(c) + i, int(r) - j, colour);
        else set(int(c) + j, int(r) + i, colour);
  }
}

double Chart::text_width(const std::string& s, double scale) const {
  return stb_easy_font_width(const_cast<char*>(s.c_str())) * scale;
}

void Chart::response_map(const std::function<double(double, double)>& f, const std::vector<double>& levels,
                         const std::vector<double>& highlight, const std::string& bar_label) {
  const int c0 = int(px(x0_)), c1 = int(px(x1_)), r0 = int(py(y1_)), r1 = int(py(y0_));
  const int nc = c1 - c0 + 1, nr = r1 - r0 + 1;
  std::vector<double> v(size_t(nc) * nr);
  double lo = INFINITY, hi = -INFINITY;
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c) {
      double x = x0_ + (c + 0.0) / (nc - 1) * (x1_ - x0_), y = y1_ - (r + 0.0) / (nr - 1) * (y1_ - y0_);
      double val = f(x, y);
      v[size_t(r) * nc + c] = val;
      lo = std::min(lo, val);
      hi = std::max(hi, val);
    }
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c) set(c0 + c, r0 + r, heat(hi > lo ? (v[size_t(r) * nc + c] - lo) / (hi - lo) : 0.5));
  // A pixel lies on a contour when the level falls between it and its right or lower neighbour.
  auto draw_level = [&](double level, Colour colour, int thick) {
    for (int r = 0; r + 1 < nr; ++r)
      for (int c = 0; c + 1 < nc; ++c) {
        double a = v[size_t(r) * nc + c] - level, b = v[size_t(r) * nc + c + 1] - level, d = v[size_t(r + 1) * nc + c] - level;
        if ((a <= 0) != (b <= 0) || (a <= 0) != (d <= 0))
          for (int t = 0; t < thick; ++t)
            for (int u = 0; u < thick; ++u) set(c0 + c + t, r0 + r + u, colour);
      }
  };
  for (double l : levels) draw_level(l, colours::grey, 1);
  for (double l : highlight) draw_level(l, colours::black, 3);
  bar_lo_ = lo;
  bar_hi_ = hi;
  bar_label_ = bar_label;
}

void Chart::draw_colour_bar() {
  if (!colour_bar_ || !(bar_hi_ > bar_lo_)) return;
  auto [left, top, right, bottom] = plot_area();
  const int c0 = right + 24, c1 = c0 + 22;
  for (int r = top; r <= bottom; ++r) {
    Colour c = heat(double(bottom - r) / double(bottom - top));
    for (int col = c0; col <= c1; ++col) set(col, r, c);
  }
  segment(c0, top, c1, top, colours::black, 1);
  segment(c0, bottom, c1, bottom, colours::black, 1);
  segment(c0, top, c0, bottom, colours::black, 1);
  segment(c1, top, c1, bottom, colours::black, 1);
  for (double t : nice_ticks(bar_lo_, bar_hi_, 5)) {
    double r = bottom - (t - bar_lo_) / (bar_hi_ - bar_lo_) * (bottom - top);
    segment(c1, r, c1 + 5, r, colours::black, 1);
    text(c1 + 9, r - 6, tick_text(t), colours::black, kTickText * 0.9);
  }
  if (!bar_label_.empty())
    text(c1 + 76, (top + bottom + text_width(bar_label_, kTickText)) / 2, bar_label_, colours::black, kTickText, true);
}

void Chart::raster(int columns, int rows, double x0, double y0, double cell,
                   const std::function<std::optional<Colour>(int, int)>& colour) {
  auto [left, top, right, bottom] = plot_area();
  for (int r = top; r <= bottom; ++r)
    for (int c = left; c <= right; ++c) {
      double x = x0_ + (c - px(x0_)) / (px(x1_) - px(x0_)) * (x1_ - x0_);
      double y = y0_ + (py(y0_) - r) / (py(y0_) - py(y1_)) * (y1_ - y0_);
      int col = int(std::floor((x - x0) / cell)), row = int(std::floor((y - y0) / cell));
      if (col < 0 || row < 0 || col >= columns || row >= rows) continue;
      if (auto value = colour(col, row)) set(c, r, *value);
    }
}

void Chart::polyline(const std::vector<double>& x, const std::vector<double>& y, Colour c, int thickness) {
  for (size_t i = 1; i < x.size() && i < y.size(); ++i)
    clipped_segment(px(x[i - 1]), py(y[i - 1]), px(x[i]), py(y[i]), c, thickness);
}

void Chart::band(const std::vector<double>& x, const std::vector<double>& low, const std::vector<double>& high, Colour c) {
  for (size_t i = 1; i < x.size(); ++i) {
    int ca = int(std::lround(px(x[i - 1]))), cb = int(std::lround(px(x[i])));
    for (int col = ca; col <= cb; ++col) {
      double t = cb > ca ? double(col - ca) / (cb - ca) : 0;
      double lo = low[i - 1] + t * (low[i] - low[i - 1]), hi = high[i - 1] + t * (high[i] - high[i - 1]);
      int ra = int(std::lround(std::max(py(hi), double(top_)))), rb = int(std::lround(std::min(py(lo), double(h_ - bottom_))));
      for (int row = ra; row <= rb; ++row) blend(col, row, c, 0.25);
    }
  }
}

void Chart::horizontal(double y, Colour c, int thickness) { clipped_segment(px(x0_), py(y), px(x1_), py(y), c, thickness); }
void Chart::vertical(double x, Colour c, int thickness) { clipped_segment(px(x), py(y0_), px(x), py(y1_), c, thickness); }

void Chart::horizontal_band(double y_low, double y_high, Colour c) {
  int ra = int(std::lround(std::max(py(y_high), double(top_)))), rb = int(std::lround(std::min(py(y_low), double(h_ - bottom_))));
  for (int row = ra; row <= rb; ++row)
    for (int col = int(px(x0_)); col <= int(px(x1_)); ++col) blend(col, row, c, 0.2);
}

void Chart::marker(double x, double y, Colour c, int radius) {
  double cc = px(x), rr = py(y);
  for (int dr = -radius; dr <= radius; ++dr)
    for (int dc = -radius; dc <= radius; ++dc)
      if (dc * dc + dr * dr <= radius * radius) set(int(std::lround(cc)) + dc, int(std::lround(rr)) + dr, c);
}

void Chart::square(double x, double y, Colour c, int half) {
  int cc = int(std::lround(px(x))), rr = int(std::lround(py(y)));
  for (int dr = -half; dr <= half; ++dr)
    for (int dc = -half; dc <= half; ++dc) set(cc + dc, rr + dr, c);
}

void Chart::error_bar(double x, double y_low, double y_high, Colour c) {
  clipped_segment(px(x), py(y_low), px(x), py(y_high), c, 1);
  for (double y : {y_low, y_high}) clipped_segment(px(x) - 4, py(y), px(x) + 4, py(y), c, 1);
}

void Chart::cross(double x, double y, Colour c, int size) {
  double cc = px(x), rr = py(y);
  segment(cc - size, rr - size, cc + size, rr + size, c, 3);
  segment(cc - size, rr + size, cc + size, rr - size, c, 3);
}

void Chart::legend(const std::vector<std::pair<std::string, Colour>>& entries) {
  double c = w_ - right_ - 10, r = top_ + 10;
  double width = 0;
  for (const auto& e : entries) width = std::max(width, text_width(e.first, kTickText));
  c -= width + 30;
  for (int row = int(r) - 4; row < int(r + 20 * entries.size()); ++row)
    for (int col = int(c) - 6; col < int(c + width + 30); ++col) blend(col, row, colours::white, 0.85);
  for (const auto& [label, colour] : entries) {
    segment(c, r + 6, c + 20, r + 6, colour, 4);
    text(c + 26, r, label, colours::black, kTickText);
    r += 20;
  }
}

void Chart::legend_above(const std::vector<std::pair<std::string, Colour>>& entries) {
  double width = 0;
  for (const auto& e : entries) width += text_width(e.first, kTickText) + 60;
  auto [left, top, right, bottom] = plot_area();
  double c = (left + right - width) / 2, r = 42;
  for (const auto& [label, colour] : entries) {
    segment(c, r + 6, c + 20, r + 6, colour, 4);
    text(c + 26, r, label, colours::black, kTickText);
    c += text_width(label, kTickText) + 60;
  }
}

void Chart::text_at(double x, double y, const std::string& s, Colour c) { text(px(x) + 6, py(y) - 8, s, c, kTickText); }

void Chart::save(const std::string& path) {
  auto [pl, pt, pr, pb] = plot_area();
  for (double t : nice_ticks(x0_, x1_)) {
    segment(px(t), pb, px(t), pb + 6, colours::black, 1);
    std::string s = tick_text(t);
    text(px(t) - text_width(s, kTickText) / 2, pb + 12, s, colours::black, kTickText);
  }
  for (double t : nice_ticks(y0_, y1_)) {
    segment(pl - 6, py(t), pl, py(t), colours::black, 1);
    std::string s = tick_text(t);
    text(pl - 12 - text_width(s, kTickText), py(t) - 6, s, colours::black, kTickText);
  }
  segment(pl, pt, pr, pt, colours::black, 1);
  segment(pl, pb, pr, pb, colours::black, 1);
  segment(pl, pt, pl, pb, colours::black, 1);
  segment(pr, pt, pr, pb, colours::black, 1);
  draw_colour_bar();
  text((w_ - text_width(title_, kTitleText)) / 2, 10, title_, colours::black, kTitleText);
  text((w_ - text_width(subtitle_, kTickText)) / 2, 40, subtitle_, colours::black, kTickText);
  text((pl + pr - text_width(x_label_, kLabelText)) / 2, h_ - 30, x_label_, colours::black, kLabelText);
  text(12, (pt + pb + text_width(y_label_, kLabelText)) / 2, y_label_, colours::black, kLabelText, true);
  // Encoded in memory, then written whole or not at all: a reader never sees half a picture, and a
  // failed write says why (stb's own file writer ignores failed writes).
  std::string png;
  auto append = [](void* to, void* data, int bytes) {
    static_cast<std::string*>(to)->append(static_cast<char*>(data), size_t(bytes));
  };
  if (!stbi_write_png_to_func(append, &png, w_, h_, 3, pixels_.data(), w_ * 3))
    throw std::runtime_error(path + ": cannot encode PNG");
  write_file_atomically(path, png);
}

}  // namespace repose
