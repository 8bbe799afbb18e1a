#include "measure/heap_scatter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "measure/heap_profile.h"
#include "measure/heap_views.h"

namespace repose {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A photograph's reading: the side asked for, or the mean of the valid slopes for "both".
double reading_of(const HeapAngle& m, const std::string& side) {
  if (side == "left") return m.left.valid ? m.left.angle_deg : kNaN;
  if (side == "right") return m.right.valid ? m.right.angle_deg : kNaN;
  return m.mean_deg;
}

double variance_of(const std::vector<double>& values) {
  const double sd = spread_of(values).sd;
  return std::isfinite(sd) ? sd * sd : kNaN;
}

// The mean of the finite values, 0 when there are none (a variance nobody measured adds nothing).
double mean_or_zero(const std::vector<double>& values) {
  const SampleSpread s = spread_of(values);
  return s.n > 0 ? s.mean : 0.0;
}

}  // namespace

double SampleSpread::se() const { return n > 0 ? sd / std::sqrt(double(n)) : kNaN; }

SampleSpread spread_of(const std::vector<double>& values) {
  SampleSpread s;
  double sum = 0, squares = 0;
  for (double v : values)
    if (std::isfinite(v)) {
      ++s.n;
      sum += v;
    }
  s.mean = s.n > 0 ? sum / s.n : kNaN;
  for (double v : values)
    if (std::isfinite(v)) squares += (v - s.mean) * (v - s.mean);
  s.sd = s.n > 1 ? std::sqrt(squares / (s.n - 1)) : kNaN;
  return s;
}

HeapReading read_heap(const std::vector<Sphere>& heap, const HeapReadingOptions& options) {
  if (heap.empty()) throw std::invalid_argument("heap reading: no spheres");
  if (options.views < 1) throw std::invalid_argument("heap reading: views must be at least 1");
  if (options.side != "left" && options.side != "right" && options.side != "both")
    throw std::invalid_argument("heap reading: side must be left, right or both, not '" + options.side + "'");
  if (!(options.turn_deg > 0 && options.turn_deg <= 45))
    throw std::invalid_argument("heap reading: the camera turn must lie in (0, 45] degrees");
  HeapReading r;
  const HeapAngle front = measure_heap_angle(heap, options.angle);
  r.front = reading_of(front, options.side);
  r.height = front.heap_height;
  const HeapProfile profile = measure_heap_profile(front);
  r.runout = options.side == "left"    ? profile.left.runout
             : options.side == "right" ? profile.right.runout
                                       : 0.5 * (profile.left.runout + profile.right.runout);

  const glm::dvec2 centre = heap_centre(heap);
  std::vector<double> turned{r.front};
  for (double turn : {-1.0, -0.5, 0.5, 1.0})
    turned.push_back(reading_of(measure_heap_angle(turned_heap(heap, centre, turn * options.turn_deg), options.angle),
                                options.side));
  r.turned_sd = spread_of(turned).sd;

  if (options.views == 1) {
    r.views_mean = r.front;
    r.per_view = {r.front};
    return r;
  }
  const HeapViewsAngle views = measure_heap_angle_views(heap, options.views, options.angle, centre);
  std::vector<double> per_view;
  for (size_t k = 0; k < views.azimuth_deg.size(); ++k) {
    const double left = views.left_deg[k], right = views.right_deg[k];
    if (options.side == "left") per_view.push_back(left);
    else if (options.side == "right") per_view.push_back(right);
    else if (std::isfinite(left) && std::isfinite(right)) per_view.push_back(0.5 * (left + right));
    else per_view.push_back(std::isfinite(left) ? left : right);
  }
  const SampleSpread s = spread_of(per_view);
  r.per_view = per_view;
  r.views_mean = s.mean;
  r.views_sd = s.n > 1 ? s.sd : 0.0;
  return r;
}

// The fill-to-fill variance of one view's reading, pooled over the views: the mean over views k of
// the variance of reading k between heaps.
double pooled_view_variance(const std::vector<HeapReading>& readings) {
  const size_t views = readings.empty() ? 0 : readings.front().per_view.size();
  std::vector<double> variances;
  for (size_t k = 0; k < views; ++k) {
    std::vector<double> view_k;
    for (const HeapReading& r : readings) {
      if (r.per_view.size() != views) throw std::invalid_argument("heap scatter: the heaps were read with different views");
      view_k.push_back(r.per_view[k]);
    }
    variances.push_back(variance_of(view_k));
  }
  return spread_of(variances).mean;
}

HeapScatter heap_scatter(const std::vector<HeapReading>& readings) {
  HeapScatter out;
  std::vector<double> front, views, height, runout, turned_var, views_var;
  for (const HeapReading& r : readings) {
    front.push_back(r.front);
    views.push_back(r.views_mean);
    height.push_back(r.height);
    runout.push_back(r.runout);
    turned_var.push_back(r.turned_sd * r.turned_sd);
    views_var.push_back(r.views_sd * r.views_sd);
  }
  out.front = spread_of(front);
  out.views_mean = spread_of(views);
  out.height = spread_of(height);
  out.runout = spread_of(runout);
  const double fit = mean_or_zero(turned_var), within = mean_or_zero(views_var);
  const double one_view = pooled_view_variance(readings);
  out.one_view_sd = std::sqrt(one_view);
  out.fit_sd = std::sqrt(fit);
  out.camera_sd = std::sqrt(std::max(0.0, within - fit));
  // Within a heap the views' readings vary by camera and fit; with one view only the turns show the fit.
  out.packing_sd = std::isfinite(one_view) ? std::sqrt(std::max(0.0, one_view - std::max(within, fit))) : kNaN;
  return out;
}

}  // namespace repose
