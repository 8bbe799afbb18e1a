#include "measure/heap_angle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "util/math.h"

namespace repose {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr size_t kMinimumPoints = 3;
// A side whose points span less than this fraction of the band's height horizontally is a
// vertical face (the heap leaning on a wall, or a body standing alone), not a slope: steeper
// than atan(1 / 0.1) = 84 degrees across the whole band.
constexpr double kSmallestSpan = 0.1;

void check_band(double low, double high) {
  if (!(low >= 0 && low < high && high <= 1))
    throw std::invalid_argument("height band must satisfy 0 <= low < high <= 1");
}


// A face steeper than any slope (kSmallestSpan) fitted as x against z, which stays well posed:
// the angle from the floor, 90 degrees for a vertical face, more where it overhangs.
SlopeFit fit_face(const std::vector<double>& x, const std::vector<double>& z, bool falling) {
  SlopeFit out;
  const LineFit inverse = fit_line(z, x);
  const double run = falling ? -inverse.slope : inverse.slope;  // horizontal run per metre of rise
  out.angle_deg = std::atan2(1.0, run) * 180.0 / kPi;
  // z = slope (x - x0) with x0 the inverse line's x at z = 0 (a vertical face: a steep stand-in).
  out.line.slope = inverse.slope != 0 ? 1.0 / inverse.slope : (falling ? -1e6 : 1e6);
  out.line.intercept = -out.line.slope * inverse.intercept;
  out.line.r_squared = inverse.r_squared;
  out.line.points = inverse.points;
  out.from = *std::min_element(x.begin(), x.end());
  out.to = *std::max_element(x.begin(), x.end());
  out.valid = true;
  return out;
}

// Fits z against x; `falling` is true where the slope should fall with x (right side, radius).
// band_height: the height range the points were taken from (m). A face steeper than a slope is a
// wall the heap leans on, unless `face_counts` (the heap's own face where nothing ran out).
SlopeFit fit_slope(const std::vector<double>& x, const std::vector<double>& z, bool falling, double band_height,
                   bool face_counts = false) {
  SlopeFit out;
  if (x.size() < kMinimumPoints) {
    out.problem = "only " + std::to_string(x.size()) + " boundary points in the height band";
    return out;
  }
  const double span = *std::max_element(x.begin(), x.end()) - *std::min_element(x.begin(), x.end());
  if (span < kSmallestSpan * band_height && face_counts) return fit_face(x, z, falling);
  if (span < kSmallestSpan * band_height) {
    out.problem = "its " + std::to_string(x.size()) + " boundary points span " + std::to_string(1e3 * span).substr(0, 5) +
                  " mm across a " + std::to_string(1e3 * band_height).substr(0, 5) +
                  " mm band: a vertical face (a wall the heap leans on), not a slope";
    return out;
  }
  try {
    out.line = fit_line(x, z);
  } catch (const std::invalid_argument& e) {
    out.problem = e.what();
    return out;
  }
  const double rise = falling ? -out.line.slope : out.line.slope;
  out.angle_deg = std::atan(rise) * 180.0 / kPi;
  out.from = *std::min_element(x.begin(), x.end());
  out.to = *std::max_element(x.begin(), x.end());
  out.valid = true;
  return out;
}

}  // namespace

double lowest_bottom(const std::vector<Sphere>& spheres) {
  double z = HUGE_VAL;
  for (const Sphere& s : spheres) z = std::min(z, s.centre.z - s.radius);
  return z;
}

HeapAngle measure_heap_angle(const std::vector<Sphere>& spheres, const HeapAngleOptions& options) {
  if (spheres.empty()) throw std::invalid_argument("heap angle: no spheres");
  const double floor_z = options.floor_z.value_or(lowest_bottom(spheres));
  double pixel = options.pixel;
  if (pixel <= 0) {
    double u_min = HUGE_VAL, u_max = -HUGE_VAL, z_max = -HUGE_VAL;
    for (const Sphere& s : spheres) {
      const double u = horizontal_coordinate(s, options.view);
      u_min = std::min(u_min, u - s.radius);
      u_max = std::max(u_max, u + s.radius);
      z_max = std::max(z_max, s.centre.z + s.radius);
    }
    pixel = std::max(u_max - u_min, z_max - floor_z) / 1600.0;
  }
  return measure_heap_image(render_silhouette(spheres, options.view, pixel, floor_z), floor_z, options);
}

HeapAngle measure_heap_image(BinaryImage image, double floor_z, const HeapAngleOptions& options) {
  check_band(options.band_low, options.band_high);
  HeapAngle out;
  out.floor_z = floor_z;
  out.image = std::move(image);
  out.holes_filled = fill_holes(out.image);
  out.profile = top_profile(out.image);
  out.visible_from = options.visible_from;
  if (options.visible_from)
    for (int c = 0; c < out.image.width && out.image.column_centre(c) < *options.visible_from; ++c)
      out.profile[static_cast<size_t>(c)] = -1;
  out.fitted_columns.assign(out.profile.size(), 0);

  // Crest: the highest profile column(s); left and right slopes start beside them.
  int crest_first = -1, crest_last = -1, crest_row = -1;
  for (int c = 0; c < out.image.width; ++c) {
    const int row = out.profile[static_cast<size_t>(c)];
    if (row > crest_row) {
      crest_row = row;
      crest_first = crest_last = c;
    } else if (row == crest_row && row >= 0) {
      crest_last = c;
    }
  }
  if (crest_row < 0)
    throw std::invalid_argument(options.visible_from ? "heap angle: nothing of the heap is visible" : "heap angle: empty silhouette");
  const double top = out.image.row_top(crest_row);
  out.heap_height = top - out.floor_z;
  if (!(out.heap_height > 0)) throw std::invalid_argument("heap angle: heap top is not above the floor");
  out.crest = 0.5 * (out.image.column_centre(crest_first) + out.image.column_centre(crest_last));
  const double z_low = out.floor_z + options.band_low * out.heap_height;
  const double z_high = out.floor_z + options.band_high * out.heap_height;

  auto collect = [&](int start, int step, uint8_t tag, std::vector<double>& u, std::vector<double>& z) {
    // Walk away from the crest while the columns stay occupied (contiguous with the heap).
    for (int c = start; c >= 0 && c < out.image.width && out.profile[static_cast<size_t>(c)] >= 0; c += step) {
      const double height = out.image.row_top(out.profile[static_cast<size_t>(c)]);
      if (height >= z_low && height <= z_high) {
        u.push_back(out.image.column_centre(c));
        z.push_back(height);
        out.fitted_columns[static_cast<size_t>(c)] = tag;
      }
    }
  };
  std::vector<double> u_left, z_left, u_right, z_right;
  collect(crest_first - 1, -1, 1, u_left, z_left);
  collect(crest_last + 1, +1, 2, u_right, z_right);
  out.left = fit_slope(u_left, z_left, false, z_high - z_low);
  // Beyond a hidden box the right face is the heap's own: cabbages standing at the opening.
  out.right = fit_slope(u_right, z_right, true, z_high - z_low, options.visible_from.has_value());

  int valid = 0;
  double sum = 0;
  for (const SlopeFit* side : {&out.left, &out.right})
    if (side->valid) {
      ++valid;
      sum += side->angle_deg;
    }
  out.mean_deg = valid ? sum / valid : kNaN;
  return out;
}

glm::dvec2 heap_centre(const std::vector<Sphere>& spheres) {
  // Volume-weighted medians: a body that rolled far away moves them by at most its share of the
  // volume, never by its distance.
  std::vector<std::pair<double, double>> xs, ys;  // (coordinate, weight)
  double total = 0;
  for (const Sphere& s : spheres) {
    const double w = s.radius * s.radius * s.radius;
    xs.push_back({s.centre.x, w});
    ys.push_back({s.centre.y, w});
    total += w;
  }
  auto weighted_median = [total](std::vector<std::pair<double, double>>& v) {
    std::sort(v.begin(), v.end());
    double running = 0;
    for (const auto& [value, weight] : v) {
      running += weight;
      if (running >= 0.5 * total) return value;
    }
    return v.back().first;
  };
  if (spheres.empty()) throw std::invalid_argument("heap angle: no spheres");
  return {weighted_median(xs), weighted_median(ys)};
}

namespace {

// The highest sphere top per (sector, radial bin) about the heap's axis, with the radius where it
// occurs.
struct SectorCell {
  double top = -HUGE_VAL, radius = 0;
  bool used = false;
};

std::vector<SectorCell> highest_tops(const std::vector<Sphere>& spheres, glm::dvec2 centre, int sectors, int bins,
                                     double bin) {
  std::vector<SectorCell> cells(static_cast<size_t>(sectors) * bins);
  for (const Sphere& s : spheres) {
    const double dx = s.centre.x - centre.x, dy = s.centre.y - centre.y;
    const double radius = std::hypot(dx, dy);
    double azimuth = std::atan2(dy, dx);
    if (azimuth < 0) azimuth += 2 * kPi;
    int sector = static_cast<int>(std::floor(azimuth / (2 * kPi) * sectors));
    sector = std::min(sector, sectors - 1);
    const int b = std::min(bins - 1, static_cast<int>(std::floor(radius / bin)));
    SectorCell& cell = cells[static_cast<size_t>(sector) * bins + b];
    const double sphere_top = s.centre.z + s.radius;
    if (!cell.used || sphere_top > cell.top) {
      cell.top = sphere_top;
      cell.radius = radius;
      cell.used = true;
    }
  }
  return cells;
}

// One sector's slope: its bins outwards from the axis until two empty ones running, those whose
// top lies in the band [z_low, z_high] fitted.
SlopeFit fit_sector(const SectorCell* bins_of_sector, int bins, double z_low, double z_high) {
  std::vector<double> radius, height;
  int empty_run = 0;
  bool started = false;
  for (int b = 0; b < bins; ++b) {
    const SectorCell& cell = bins_of_sector[b];
    if (!cell.used) {
      if (started && ++empty_run >= 2) break;
      continue;
    }
    started = true;
    empty_run = 0;
    if (cell.top >= z_low && cell.top <= z_high) {
      radius.push_back(cell.radius);
      height.push_back(cell.top);
    }
  }
  return fit_slope(radius, height, true, z_high - z_low);
}

// Mean, sample spread, least and greatest of the valid sectors' angles (NaN without one).
void summarise_sectors(const std::vector<double>& fitted_angles, AxisymmetricHeapAngle& out) {
  out.valid_sectors = static_cast<int>(fitted_angles.size());
  if (fitted_angles.empty()) {
    out.mean_deg = out.spread_deg = out.min_deg = out.max_deg = kNaN;
    return;
  }
  double sum = 0;
  for (double a : fitted_angles) sum += a;
  out.mean_deg = sum / fitted_angles.size();
  double squares = 0;
  for (double a : fitted_angles) squares += (a - out.mean_deg) * (a - out.mean_deg);
  out.spread_deg = fitted_angles.size() > 1 ? std::sqrt(squares / (fitted_angles.size() - 1)) : 0.0;
  out.min_deg = *std::min_element(fitted_angles.begin(), fitted_angles.end());
  out.max_deg = *std::max_element(fitted_angles.begin(), fitted_angles.end());
}

}  // namespace

AxisymmetricHeapAngle measure_axisymmetric_heap_angle(const std::vector<Sphere>& spheres,
                                                      const AxisymmetricOptions& options) {
  if (spheres.empty()) throw std::invalid_argument("heap angle: no spheres");
  if (options.sectors < 1) throw std::invalid_argument("heap angle: sectors must be at least 1");
  check_band(options.band_low, options.band_high);
  AxisymmetricHeapAngle out;
  out.floor_z = options.floor_z.value_or(lowest_bottom(spheres));

  out.centre = options.centre ? *options.centre : heap_centre(spheres);

  double top = -HUGE_VAL, largest_radius = 0;
  for (const Sphere& s : spheres) {
    top = std::max(top, s.centre.z + s.radius);
    largest_radius = std::max(largest_radius, std::hypot(s.centre.x - out.centre.x, s.centre.y - out.centre.y));
  }
  out.heap_height = top - out.floor_z;
  if (!(out.heap_height > 0)) throw std::invalid_argument("heap angle: heap top is not above the floor");
  const double bin = options.bin_width > 0 ? options.bin_width : largest_radius / 25.0;
  if (!(bin > 0)) throw std::invalid_argument("heap angle: all spheres lie on the axis; give a bin width");
  const int bins = static_cast<int>(std::floor(largest_radius / bin)) + 1;
  const double z_low = out.floor_z + options.band_low * out.heap_height;
  const double z_high = out.floor_z + options.band_high * out.heap_height;

  std::vector<SectorCell> cells = highest_tops(spheres, out.centre, options.sectors, bins, bin);
  std::vector<double> fitted_angles;
  for (int sector = 0; sector < options.sectors; ++sector) {
    SectorFit result;
    result.from_deg = 360.0 * sector / options.sectors;
    result.to_deg = 360.0 * (sector + 1) / options.sectors;
    result.fit = fit_sector(&cells[static_cast<size_t>(sector) * bins], bins, z_low, z_high);
    if (result.fit.valid) fitted_angles.push_back(result.fit.angle_deg);
    out.sectors.push_back(result);
  }
  summarise_sectors(fitted_angles, out);
  return out;
}

std::string describe_sector_fit(const AxisymmetricHeapAngle& fit) {
  char text[256];
  if (fit.valid_sectors > 0) {
    std::snprintf(text, sizeof text, "mean %.2f deg, spread %.2f deg over %d of %zu sectors", fit.mean_deg,
                  fit.spread_deg, fit.valid_sectors, fit.sectors.size());
    return text;
  }
  std::string why = fit.sectors.empty() ? "no sectors" : fit.sectors[0].fit.problem;
  std::snprintf(text, sizeof text, "no sector gave a slope (sector %.0f-%.0f deg: ", fit.sectors.empty() ? 0.0 : fit.sectors[0].from_deg,
                fit.sectors.empty() ? 0.0 : fit.sectors[0].to_deg);
  return text + why + ")";
}

}  // namespace repose
