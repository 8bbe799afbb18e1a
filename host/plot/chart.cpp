#include "plot/chart.h"

#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
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

bool same_colour(Colour a, Colour b) { return a == b; }

std::map<std::string, ChartRecord>* kept_records = nullptr;

}  // namespace

// Ticks at 1, 2 or 5 times a power of ten, about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target) {
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


std::vector<std::string> tick_labels(const std::vector<double>& ticks) {
  std::vector<std::string> out;
  for (int digits = 4; digits <= 12; ++digits) {
    out.clear();
    for (double t : ticks) out.push_back(format_g(t, digits));
    bool distinct = true;
    for (size_t i = 1; i < out.size(); ++i) distinct = distinct && out[i] != out[i - 1];
    if (distinct) break;
  }
  return out;
}

int ChartRecord::points_of(Colour c, Mark m) const {
  for (const auto& [entry, count] : points)
    if (same_colour(entry.colour, c) && entry.mark == m) return count;
  return 0;
}

void Chart::keep_records() {
  if (!kept_records) kept_records = new std::map<std::string, ChartRecord>();
}

ChartRecord Chart::recorded(const std::string& path) {
  if (!kept_records) throw std::logic_error("Chart::recorded: call Chart::keep_records() first");
  auto found = kept_records->find(path);
  if (found == kept_records->end()) throw std::out_of_range("no chart was saved as " + path);
  return found->second;
}

// Counts a data point drawn at pixel (c, r) when it lies inside the plot area.
void Chart::count_point(double c, double r, Colour colour, Mark mark) {
  auto [left, top, right, bottom] = plot_area();
  if (!(c >= left - 0.5 && c <= right + 0.5 && r >= top - 0.5 && r <= bottom + 0.5)) return;
  if (mark != Mark::Band) data_pixels_.push_back({int(std::lround(c)), int(std::lround(r))});
  for (auto& [entry, count] : record_.points)
    if (same_colour(entry.colour, colour) && entry.mark == mark) {
      ++count;
      return;
    }
  record_.points.push_back({LegendEntry{"", colour, mark}, 1});
}

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
  // The highlighted contours are a series of their own (a legend may name them): their pixels count.
  auto draw_level = [&](double level, Colour colour, int thick, bool counted) {
    for (int r = 0; r + 1 < nr; ++r)
      for (int c = 0; c + 1 < nc; ++c) {
        double a = v[size_t(r) * nc + c] - level, b = v[size_t(r) * nc + c + 1] - level, d = v[size_t(r + 1) * nc + c] - level;
        if ((a <= 0) != (b <= 0) || (a <= 0) != (d <= 0)) {
          for (int t = 0; t < thick; ++t)
            for (int u = 0; u < thick; ++u) set(c0 + c + t, r0 + r + u, colour);
          if (counted) count_point(c0 + c, r0 + r, colour, Mark::Line);
        }
      }
  };
  for (double l : levels) draw_level(l, colours::grey, 1, false);
  for (double l : highlight) draw_level(l, colours::black, 3, true);
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
  std::vector<double> ticks = nice_ticks(bar_lo_, bar_hi_, 5);
  record_.bar_ticks = tick_labels(ticks);
  for (size_t i = 0; i < ticks.size(); ++i) {
    double r = bottom - (ticks[i] - bar_lo_) / (bar_hi_ - bar_lo_) * (bottom - top);
    segment(c1, r, c1 + 5, r, colours::black, 1);
    text(c1 + 9, r - 6, record_.bar_ticks[i], colours::black, kTickText * 0.9);
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
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) count_point(px(x[i]), py(y[i]), c, Mark::Line);
}

void Chart::band(const std::vector<double>& x, const std::vector<double>& low, const std::vector<double>& high, Colour c) {
  for (size_t i = 1; i < x.size(); ++i) {
    int ca = int(std::lround(px(x[i - 1]))), cb = int(std::lround(px(x[i])));
    // A column shared with the next segment is its first: blended twice it would draw a stripe.
    const int last = i + 1 < x.size() ? cb - 1 : cb;
    for (int col = ca; col <= last; ++col) {
      double t = cb > ca ? double(col - ca) / (cb - ca) : 0;
      double lo = low[i - 1] + t * (low[i] - low[i - 1]), hi = high[i - 1] + t * (high[i] - high[i - 1]);
      int ra = int(std::lround(std::max(py(hi), double(top_)))), rb = int(std::lround(std::min(py(lo), double(h_ - bottom_))));
      for (int row = ra; row <= rb; ++row) blend(col, row, c, 0.25);
      if (rb >= ra) band_columns_.push_back({col, ra, rb});
    }
  }
  for (size_t i = 0; i < x.size(); ++i) count_point(px(x[i]), py(0.5 * (low[i] + high[i])), c, Mark::Band);
}

// Reference lines count as a line series (a legend entry may name them) but not as data to keep clear.
void Chart::horizontal(double y, Colour c, int thickness) {
  clipped_segment(px(x0_), py(y), px(x1_), py(y), c, thickness);
  size_t kept = data_pixels_.size();
  count_point(0.5 * (px(x0_) + px(x1_)), py(y), c, Mark::Line);
  data_pixels_.resize(kept);
  reference_rows_.push_back({int(py(y)) - thickness, int(py(y)) + thickness});
}
void Chart::vertical(double x, Colour c, int thickness) {
  clipped_segment(px(x), py(y0_), px(x), py(y1_), c, thickness);
  size_t kept = data_pixels_.size();
  count_point(px(x), 0.5 * (py(y0_) + py(y1_)), c, Mark::Line);
  data_pixels_.resize(kept);
  reference_cols_.push_back({int(px(x)) - thickness, int(px(x)) + thickness});
}

void Chart::horizontal_band(double y_low, double y_high, Colour c) {
  int ra = int(std::lround(std::max(py(y_high), double(top_)))), rb = int(std::lround(std::min(py(y_low), double(h_ - bottom_))));
  for (int row = ra; row <= rb; ++row)
    for (int col = int(px(x0_)); col <= int(px(x1_)); ++col) blend(col, row, c, 0.2);
  count_point(0.5 * (px(x0_) + px(x1_)), py(0.5 * (y_low + y_high)), c, Mark::Band);
  reference_rows_.push_back({ra, rb});
}

void Chart::marker(double x, double y, Colour c, int radius) {
  double cc = px(x), rr = py(y);
  for (int dr = -radius; dr <= radius; ++dr)
    for (int dc = -radius; dc <= radius; ++dc)
      if (dc * dc + dr * dr <= radius * radius) set(int(std::lround(cc)) + dc, int(std::lround(rr)) + dr, c);
  count_point(cc, rr, c, Mark::Dot);
}

void Chart::square(double x, double y, Colour c, int half) {
  int cc = int(std::lround(px(x))), rr = int(std::lround(py(y)));
  for (int dr = -half; dr <= half; ++dr)
    for (int dc = -half; dc <= half; ++dc) set(cc + dc, rr + dr, c);
  count_point(cc, rr, c, Mark::Square);
}

// Its ends and middle are kept clear of the legend like a data point, but are not points.
void Chart::error_bar(double x, double y_low, double y_high, Colour c) {
  clipped_segment(px(x), py(y_low), px(x), py(y_high), c, 1);
  for (double y : {y_low, y_high}) clipped_segment(px(x) - 4, py(y), px(x) + 4, py(y), c, 1);
  auto [left, top, right, bottom] = plot_area();
  for (double y : {y_low, 0.5 * (y_low + y_high), y_high}) {
    double r = std::clamp(py(y), double(top), double(bottom));
    if (px(x) >= left && px(x) <= right) data_pixels_.push_back({int(std::lround(px(x))), int(std::lround(r))});
  }
}

void Chart::cross(double x, double y, Colour c, int size) {
  double cc = px(x), rr = py(y);
  segment(cc - size, rr - size, cc + size, rr + size, c, 3);
  segment(cc - size, rr + size, cc + size, rr - size, c, 3);
  count_point(cc, rr, c, Mark::Cross);
}

// Scanline fill between the polygon's edges (pixel centres inside by the even-odd rule), then
// its outline.
void Chart::polygon(const std::vector<double>& x, const std::vector<double>& y, Colour fill, Colour edge, Mark mark) {
  size_t n = std::min(x.size(), y.size());
  if (n < 3) return;
  std::vector<double> c(n), r(n);
  double r_lo = 1e300, r_hi = -1e300, c_mean = 0, r_mean = 0;
  for (size_t k = 0; k < n; ++k) {
    c[k] = px(x[k]);
    r[k] = py(y[k]);
    r_lo = std::min(r_lo, r[k]);
    r_hi = std::max(r_hi, r[k]);
    c_mean += c[k] / double(n);
    r_mean += r[k] / double(n);
  }
  for (int row = int(std::ceil(r_lo)); row <= int(std::floor(r_hi)); ++row) {
    std::vector<double> crossings;
    for (size_t k = 0; k < n; ++k) {
      size_t l = (k + 1) % n;
      if ((r[k] <= row) != (r[l] <= row)) crossings.push_back(c[k] + (row - r[k]) / (r[l] - r[k]) * (c[l] - c[k]));
    }
    std::sort(crossings.begin(), crossings.end());
    for (size_t k = 0; k + 1 < crossings.size(); k += 2)
      for (int col = int(std::ceil(crossings[k])); col <= int(std::floor(crossings[k + 1])); ++col) set(col, row, fill);
  }
  for (size_t k = 0; k < n; ++k) clipped_segment(c[k], r[k], c[(k + 1) % n], r[(k + 1) % n], edge, 1);
  count_point(c_mean, r_mean, fill, mark);
}

void Chart::hide_axes(std::vector<std::string> x_ticks, std::vector<std::string> y_ticks, std::string z_label,
                      std::vector<std::string> z_ticks) {
  axes_ = false;
  record_.x_ticks = std::move(x_ticks);
  record_.y_ticks = std::move(y_ticks);
  record_.z_label = std::move(z_label);
  record_.z_ticks = std::move(z_ticks);
}

void Chart::legend(const std::vector<LegendEntry>& entries) { box_legend_ = entries; }

// The sample of an entry: its line, dot, square or cross, or a patch of its band.
void Chart::draw_legend_mark(double c, double r, const LegendEntry& e) {
  switch (e.mark) {
    case Mark::Line: segment(c, r + 6, c + 20, r + 6, e.colour, 4); break;
    case Mark::Dot:
      for (int dr = -4; dr <= 4; ++dr)
        for (int dc = -4; dc <= 4; ++dc)
          if (dc * dc + dr * dr <= 16) set(int(c) + 10 + dc, int(r) + 6 + dr, e.colour);
      break;
    case Mark::Square:
      for (int dr = -3; dr <= 3; ++dr)
        for (int dc = -3; dc <= 3; ++dc) set(int(c) + 10 + dc, int(r) + 6 + dr, e.colour);
      break;
    case Mark::Cross:
      segment(c + 4, r, c + 16, r + 12, e.colour, 3);
      segment(c + 4, r + 12, c + 16, r, e.colour, 3);
      break;
    case Mark::Band:
      for (int dr = -1; dr <= 13; ++dr)
        for (int dc = 0; dc <= 20; ++dc) blend(int(c) + dc, int(r) + dr, e.colour, 0.35);
      break;
    case Mark::Bar:
      for (int dr = 0; dr <= 12; ++dr)
        for (int dc = 2; dc <= 18; ++dc) set(int(c) + dc, int(r) + dr, e.colour);
      break;
  }
}

// The area of reference lines and bands (horizontal ones and a model's) under a legend box at (c, r).
double Chart::reference_overlap(double c, double r, double box_w, double box_h) const {
  auto overlap = [](double a0, double a1, double b0, double b1) { return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)); };
  double area = 0;
  for (const auto& [first, last] : reference_rows_) area += overlap(r, r + box_h, first, last + 1) * box_w;
  for (const auto& [first, last] : reference_cols_) area += overlap(c, c + box_w, first, last + 1) * box_h;
  for (const auto& [col, first, last] : band_columns_)
    if (col >= c && col < c + box_w) area += overlap(r, r + box_h, first, last + 1);
  return area;
}

// The legend box goes into the plot corner that covers the fewest data points, and among those
// the least of the reference lines and bands (a measured value's band is read as much as a point).
void Chart::draw_legend_box() {
  const auto& entries = box_legend_;
  if (entries.empty()) return;
  record_.legend.insert(record_.legend.end(), entries.begin(), entries.end());
  double width = 0;
  for (const auto& e : entries) width = std::max(width, text_width(e.label, kTickText));
  const double box_w = width + 36, box_h = 20.0 * entries.size() + 4;
  auto [left, top, right, bottom] = plot_area();
  const std::array<std::array<double, 2>, 4> corners = {{{right - 10 - box_w, top + 6.0},
                                                         {left + 10.0, top + 6.0},
                                                         {right - 10 - box_w, bottom - 6 - box_h},
                                                         {left + 10.0, bottom - 6 - box_h}}};
  size_t best = 0, best_hidden = SIZE_MAX;
  double best_overlap = 0;
  for (size_t k = 0; k < corners.size(); ++k) {
    size_t hidden = 0;
    for (const auto& p : data_pixels_)
      hidden += p[0] >= corners[k][0] - 4 && p[0] <= corners[k][0] + box_w + 4 && p[1] >= corners[k][1] - 4 &&
                p[1] <= corners[k][1] + box_h + 4;
    double overlap = reference_overlap(corners[k][0] - 4, corners[k][1] - 4, box_w + 8, box_h + 8);
    if (hidden < best_hidden || (hidden == best_hidden && overlap < best_overlap))
      best = k, best_hidden = hidden, best_overlap = overlap;
  }
  record_.legend_covers_data = best_hidden > 0;
  record_.legend_covers_reference = best_overlap > 0;
  double c = corners[best][0] + 6, r = corners[best][1] + 4;
  for (int row = int(r) - 4; row < int(r + box_h); ++row)
    for (int col = int(c) - 6; col < int(c + box_w - 6); ++col) blend(col, row, colours::white, 0.85);
  for (const auto& e : entries) {
    draw_legend_mark(c, r, e);
    text(c + 26, r, e.label, colours::black, kTickText);
    r += 20;
  }
}

void Chart::legend_above(const std::vector<LegendEntry>& entries) {
  record_.legend.insert(record_.legend.end(), entries.begin(), entries.end());
  double width = 0;
  for (const auto& e : entries) width += text_width(e.label, kTickText) + 60;
  auto [left, top, right, bottom] = plot_area();
  double c = (left + right - width) / 2, r = 42;
  for (const auto& e : entries) {
    draw_legend_mark(c, r, e);
    text(c + 26, r, e.label, colours::black, kTickText);
    c += text_width(e.label, kTickText) + 60;
  }
}

void Chart::text_at(double x, double y, const std::string& s, Colour c) { text(px(x) + 6, py(y) - 8, s, c, kTickText); }

void Chart::save(const std::string& path) {
  auto [pl, pt, pr, pb] = plot_area();
  std::vector<double> xt = nice_ticks(x0_, x1_), yt = nice_ticks(y0_, y1_);
  if (!axes_) xt.clear(), yt.clear();
  else record_.x_ticks = tick_labels(xt), record_.y_ticks = tick_labels(yt);
  for (size_t i = 0; i < xt.size(); ++i) {
    segment(px(xt[i]), pb, px(xt[i]), pb + 6, colours::black, 1);
    const std::string& s = record_.x_ticks[i];
    text(px(xt[i]) - text_width(s, kTickText) / 2, pb + 12, s, colours::black, kTickText);
  }
  for (size_t i = 0; i < yt.size(); ++i) {
    segment(pl - 6, py(yt[i]), pl, py(yt[i]), colours::black, 1);
    const std::string& s = record_.y_ticks[i];
    text(pl - 12 - text_width(s, kTickText), py(yt[i]) - 6, s, colours::black, kTickText);
  }
  if (axes_) {
    segment(pl, pt, pr, pt, colours::black, 1);
    segment(pl, pb, pr, pb, colours::black, 1);
    segment(pl, pt, pl, pb, colours::black, 1);
    segment(pr, pt, pr, pb, colours::black, 1);
  }
  draw_colour_bar();
  draw_legend_box();
  record_.title = title_;
  record_.subtitle = subtitle_;
  record_.x_label = x_label_;
  record_.y_label = y_label_;
  text((w_ - text_width(title_, kTitleText)) / 2, 10, title_, colours::black, kTitleText);
  text((w_ - text_width(subtitle_, kTickText)) / 2, 40, subtitle_, colours::black, kTickText);
  if (axes_) {  // a picture without axes writes its labels where its own axes are
    text((pl + pr - text_width(x_label_, kLabelText)) / 2, h_ - 30, x_label_, colours::black, kLabelText);
    text(12, (pt + pb + text_width(y_label_, kLabelText)) / 2, y_label_, colours::black, kLabelText, true);
  }
  // Encoded in memory, then written whole or not at all: a reader never sees half a picture, and a
  // failed write says why (stb's own file writer ignores failed writes).
  std::string png;
  auto append = [](void* to, void* data, int bytes) {
    static_cast<std::string*>(to)->append(static_cast<char*>(data), size_t(bytes));
  };
  if (!stbi_write_png_to_func(append, &png, w_, h_, 3, pixels_.data(), w_ * 3))
    throw std::runtime_error(path + ": cannot encode PNG");
  write_file_atomically(path, png);
  if (kept_records) (*kept_records)[path] = record_;
}

}  // namespace repose
