#include "measure/heap_profile.h"

#include <cmath>
#include <stdexcept>

namespace repose {
namespace {

constexpr size_t kMinimumPoints = 3;

double det3(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Least-squares parabola z = a + b x + c x^2 about the points' mean x, scaled by their half span
// (well conditioned whatever the units): {b, c} per unit of the original x. False when degenerate.
bool fit_parabola(const std::vector<double>& u, const std::vector<double>& z, double& b, double& c) {
  double mean = 0, lo = u.front(), hi = u.front();
  for (double v : u) {
    mean += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  mean /= double(u.size());
  double half = 0.5 * (hi - lo);
  if (!(half > 0)) return false;
  double s[5] = {0, 0, 0, 0, 0}, t[3] = {0, 0, 0};
  for (size_t k = 0; k < u.size(); ++k) {
    double x = (u[k] - mean) / half, p = 1;
    for (int e = 0; e < 5; ++e) {
      if (e < 3) t[e] += p * z[k];
      s[e] += p;
      p *= x;
    }
  }
  const double m[3][3] = {{s[0], s[1], s[2]}, {s[1], s[2], s[3]}, {s[2], s[3], s[4]}};
  double d = det3(m);
  if (!(std::abs(d) > 1e-12 * s[0] * s[2] * s[4])) return false;
  double coef[3];
  for (int col = 0; col < 3; ++col) {
    double r[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r[i][j] = j == col ? t[i] : m[i][j];
    coef[col] = det3(r) / d;
  }
  b = coef[1] / half;
  c = coef[2] / (half * half);
  return true;
}

SlopeProfile side_profile(const HeapAngle& heap, int start, int step, const HeapProfileOptions& options) {
  SlopeProfile out;
  const BinaryImage& image = heap.image;
  const double z_low = heap.floor_z + options.band_low * heap.heap_height;
  const double z_high = heap.floor_z + options.band_high * heap.heap_height;
  std::vector<double> u, z;
  int last = start - step;
  for (int c = start; c >= 0 && c < image.width && heap.profile[size_t(c)] >= 0; c += step) {
    last = c;
    double top = image.row_top(heap.profile[size_t(c)]);
    if (top < z_low || top > z_high) continue;
    u.push_back(image.column_centre(c));
    z.push_back(top);
  }
  // The toe is the far edge of the last contiguous column.
  out.toe = image.column_centre(last) + 0.5 * step * image.pixel;
  out.runout = std::abs(out.toe - heap.crest);
  out.points = u.size();
  if (u.size() < kMinimumPoints) {
    out.problem = "only " + std::to_string(u.size()) + " profile columns in the height band";
    return out;
  }
  double b = 0, c = 0;
  if (!fit_parabola(u, z, b, c) || b == 0) {
    out.problem = "the profile does not fall across the band";
    return out;
  }
  double lo = u.front(), hi = u.front();
  for (double v : u) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  out.convexity = -c * (hi - lo) / (4 * std::abs(b));
  out.valid = true;
  return out;
}

}  // namespace

HeapProfile measure_heap_profile(const HeapAngle& heap, const HeapProfileOptions& options) {
  if (!(options.band_low >= 0 && options.band_low < options.band_high && options.band_high <= 1))
    throw std::invalid_argument("heap profile: height band must satisfy 0 <= low < high <= 1");
  if (heap.profile.empty()) throw std::invalid_argument("heap profile: the picture is empty");
  HeapProfile out;
  out.height = heap.heap_height;
  // The crest columns as measure_heap_angle found them: the highest profile row.
  int crest_row = -1, first = -1, last = -1;
  for (int c = 0; c < heap.image.width; ++c) {
    int row = heap.profile[size_t(c)];
    if (row > crest_row) {
      crest_row = row;
      first = last = c;
    } else if (row == crest_row && row >= 0) {
      last = c;
    }
  }
  out.left = side_profile(heap, first - 1, -1, options);
  out.right = side_profile(heap, last + 1, +1, options);
  return out;
}

}  // namespace repose
