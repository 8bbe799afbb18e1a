#include "calibrate/plot.h"

#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "util/number_text.h"

namespace repose::calibrate {

const std::vector<Colour>& colours::series() {
  static const std::vector<Colour> s = {blue, red, green, orange, purple, {0, 150, 160}, {120, 80, 40}, grey};
  return s;
}

namespace {

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

}  // namespace

Chart::Chart(int width, int height, double x0, double x1, double y0, double y1)
    : w_(width), h_(height), x0_(x0), x1_(x1), y0_(y0), y1_(y1), pixels_(size_t(width) * height * 3, 255) {
  auto widen = [](double& a, double& b) {
    if (!(b > a)) {
      double pad = a == 0 ? 1 : 0.05 * std::abs(a);
      a -= pad;
      b += pad;
    }
  };
  widen(x0_, x1_);
  widen(y0_, y1_);
}

void Chart::title(const std::string& t) { title_ = t; }
void Chart::labels(const std::string& x, const std::string& y) {
  x_label_ = x;
  y_label_ = y;
}

double Chart::px(double x) const { return left_ + (x - x0_) / (x1_ - x0_) * (w_ - left_ - right_); }
double Chart::py(double y) const { return (h_ - bottom_) - (y - y0_) / (y1_ - y0_) * (h_ - top_ - bottom_); }

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

void Chart::text(double c, double r, const std::string& s, Colour colour, double scale) {
  static char buffer[99999];
  int quads = stb_easy_font_print(0, 0, const_cast<char*>(s.c_str()), nullptr, buffer, sizeof buffer);
  const float* v = reinterpret_cast<const float*>(buffer);
  for (int q = 0; q < quads; ++q) {
    const float* a = v + q * 16;  // 4 vertices of (x, y, z, colour) = 16 bytes each
    double qx0 = a[0], qy0 = a[1], qx1 = a[8], qy1 = a[9];
    for (int rr = int(std::floor(r + qy0 * scale)); rr < int(std::floor(r + qy1 * scale)); ++rr)
      for (int cc = int(std::floor(c + qx0 * scale)); cc < int(std::floor(c + qx1 * scale)); ++cc) set(cc, rr, colour);
  }
}

double Chart::text_width(const std::string& s, double scale) const {
  return stb_easy_font_width(const_cast<char*>(s.c_str())) * scale;
}

void Chart::response_map(const std::function<double(double, double)>& f, const std::vector<double>& levels,
                         const std::vector<double>& highlight) {
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
}

void Chart::polyline(const std::vector<double>& x, const std::vector<double>& y, Colour c, int thickness) {
  for (size_t i = 1; i < x.size() && i < y.size(); ++i) segment(px(x[i - 1]), py(y[i - 1]), px(x[i]), py(y[i]), c, thickness);
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

void Chart::horizontal(double y, Colour c, int thickness) { segment(px(x0_), py(y), px(x1_), py(y), c, thickness); }
void Chart::vertical(double x, Colour c, int thickness) { segment(px(x), py(y0_), px(x), py(y1_), c, thickness); }

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

void Chart::cross(double x, double y, Colour c, int size) {
  double cc = px(x), rr = py(y);
  segment(cc - size, rr - size, cc + size, rr + size, c, 3);
  segment(cc - size, rr + size, cc + size, rr - size, c, 3);
}

void Chart::legend(const std::vector<std::pair<std::string, Colour>>& entries) {
  double c = w_ - right_ - 10, r = top_ + 8;
  double width = 0;
  for (const auto& e : entries) width = std::max(width, text_width(e.first, 1.5));
  c -= width + 26;
  for (const auto& [label, colour] : entries) {
    segment(c, r + 5, c + 18, r + 5, colour, 3);
    text(c + 24, r, label, colours::black, 1.5);
    r += 18;
  }
}

void Chart::text_at(double x, double y, const std::string& s, Colour c) { text(px(x) + 6, py(y) - 6, s, c, 1.5); }

void Chart::save(const std::string& path) {
  const double pl = px(x0_), pr = px(x1_), pt = py(y1_), pb = py(y0_);
  for (double t : nice_ticks(x0_, x1_)) {
    segment(px(t), pb, px(t), pb + 5, colours::black, 1);
    std::string s = tick_text(t);
    text(px(t) - text_width(s, 1.5) / 2, pb + 10, s, colours::black, 1.5);
  }
  for (double t : nice_ticks(y0_, y1_)) {
    segment(pl - 5, py(t), pl, py(t), colours::black, 1);
    std::string s = tick_text(t);
    text(pl - 10 - text_width(s, 1.5), py(t) - 5, s, colours::black, 1.5);
  }
  segment(pl, pt, pr, pt, colours::black, 1);
  segment(pl, pb, pr, pb, colours::black, 1);
  segment(pl, pt, pl, pb, colours::black, 1);
  segment(pr, pt, pr, pb, colours::black, 1);
  text((w_ - text_width(title_, 2)) / 2, 10, title_, colours::black, 2);
  text((pl + pr - text_width(x_label_, 1.8)) / 2, h_ - 28, x_label_, colours::black, 1.8);
  text(8, top_ - 18, y_label_, colours::black, 1.8);
  // Written beside the target and renamed over it: a reader never sees half a picture.
  const std::string partial = path + ".partial";
  if (!stbi_write_png(partial.c_str(), w_, h_, 3, pixels_.data(), w_ * 3)) throw std::runtime_error(path + ": cannot write PNG");
  std::filesystem::rename(partial, path);
}

}  // namespace repose::calibrate
