#include "measure/heap_json.h"

#include <cmath>

namespace repose {

using Json = nlohmann::ordered_json;

namespace {
// An angle that was not measured (NaN) is null.
Json angle_or_null(double a) { return std::isfinite(a) ? Json(a) : Json(nullptr); }
}  // namespace

Json slope_json(const SlopeFit& f) {
  Json j;
  j["valid"] = f.valid;
  if (!f.valid) {
    j["problem"] = f.problem;
    return j;
  }
  j["angle_deg"] = f.angle_deg;
  j["from"] = f.from;
  j["to"] = f.to;
  j["slope"] = f.line.slope;
  j["intercept"] = f.line.intercept;
  j["r_squared"] = f.line.r_squared;
  j["points"] = f.line.points;
  return j;
}

Json profile_json(const SlopeProfile& p) {
  Json j;
  j["runout"] = p.runout;
  j["toe"] = p.toe;
  j["valid"] = p.valid;
  j["convexity"] = p.valid ? Json(p.convexity) : Json(nullptr);
  if (p.valid)
    j["points"] = p.points;
  else
    j["problem"] = p.problem;
  return j;
}

Json views_json(const HeapViewsAngle& views) {
  Json v;
  v["mean_deg"] = views.mean_deg;
  v["sd_deg"] = views.sd_deg;
  v["valid_slopes"] = views.valid_slopes;
  v["centre"] = {views.centre.x, views.centre.y};
  Json per = Json::array();
  for (size_t k = 0; k < views.azimuth_deg.size(); ++k)
    per.push_back({{"azimuth_deg", views.azimuth_deg[k]},
                   {"left_deg", angle_or_null(views.left_deg[k])},
                   {"right_deg", angle_or_null(views.right_deg[k])}});
  v["per_view"] = per;
  return v;
}

Json axisymmetric_json(const AxisymmetricHeapAngle& heap) {
  Json a;
  a["mean_deg"] = heap.mean_deg;
  a["spread_deg"] = heap.spread_deg;
  a["min_deg"] = heap.min_deg;
  a["max_deg"] = heap.max_deg;
  a["valid_sectors"] = heap.valid_sectors;
  a["centre"] = {heap.centre.x, heap.centre.y};
  Json sectors = Json::array();
  for (const SectorFit& s : heap.sectors) {
    Json e = slope_json(s.fit);
    e["from_deg"] = s.from_deg;
    e["to_deg"] = s.to_deg;
    sectors.push_back(e);
  }
  a["sectors"] = sectors;
  return a;
}

}  // namespace repose
