#include "measure/heap_views.h"

#include <cstdio>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "util/math.h"

namespace repose {

std::vector<Sphere> turned_heap(const std::vector<Sphere>& spheres, glm::dvec2 centre, double azimuth_deg) {
  const double a = azimuth_deg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
  std::vector<Sphere> turned(spheres.size());
  // Turning the heap by -a about the axis is the camera turning by +a around it.
  for (size_t i = 0; i < spheres.size(); ++i) {
    const double dx = spheres[i].centre.x - centre.x, dy = spheres[i].centre.y - centre.y;
    turned[i] = {{c * dx + s * dy, -s * dx + c * dy, spheres[i].centre.z}, spheres[i].radius};
  }
  return turned;
}

HeapViewsAngle measure_heap_angle_views(const std::vector<Sphere>& spheres, int views, const HeapAngleOptions& options,
                                        std::optional<glm::dvec2> centre) {
  if (views < 1) throw std::invalid_argument("heap angle: views must be at least 1");
  if (spheres.empty()) throw std::invalid_argument("heap angle: no spheres");
  HeapViewsAngle out;
  out.centre = centre ? *centre : heap_centre(spheres);
  HeapAngleOptions front = options;  // the turn keeps every z: each view finds the same floor
  front.view = ViewAxis::Y;
  std::vector<double> slopes;
  for (int k = 0; k < views; ++k) {
    const double azimuth = 180.0 * k / views;
    const HeapAngle view = measure_heap_angle(turned_heap(spheres, out.centre, azimuth), front);
    out.azimuth_deg.push_back(azimuth);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out.left_deg.push_back(view.left.valid ? view.left.angle_deg : nan);
    out.right_deg.push_back(view.right.valid ? view.right.angle_deg : nan);
    for (const SlopeFit* f : {&view.left, &view.right})
      if (f->valid) slopes.push_back(f->angle_deg);
  }
  out.valid_slopes = int(slopes.size());
  double sum = 0, squares = 0;
  for (double v : slopes) sum += v;
  out.mean_deg = slopes.empty() ? std::numeric_limits<double>::quiet_NaN() : sum / double(slopes.size());
  for (double v : slopes) squares += (v - out.mean_deg) * (v - out.mean_deg);
  out.sd_deg = slopes.size() > 1 ? std::sqrt(squares / double(slopes.size() - 1)) : 0.0;
  return out;
}

std::string describe_views(const HeapViewsAngle& v) {
  char text[160];
  if (v.valid_slopes == 0) {
    std::snprintf(text, sizeof text, "no slope in any of %zu views", v.azimuth_deg.size());
    return text;
  }
  std::snprintf(text, sizeof text, "mean %.2f deg, sd %.2f deg over %d slopes of %zu views", v.mean_deg, v.sd_deg,
                v.valid_slopes, v.azimuth_deg.size());
  return text;
}

}  // namespace repose
