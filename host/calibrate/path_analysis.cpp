#include "calibrate/path_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "util/number_text.h"

namespace repose::calibrate {

namespace {

// The path's points in order, each with the mean and standard error of every response there.
std::vector<PathPoint> path_points(const CampaignPlan& plan, const std::vector<Observations>& obs,
                                   std::vector<NoiseEstimate>& noise) {
  std::vector<PathPoint> points;
  const Observations& first = obs.front();
  for (int i = 0; i < first.x.rows(); ++i) {
    size_t p = 0;
    while (p < points.size() && points[p].coded != first.x.row(i).transpose()) ++p;
    if (p == points.size()) points.push_back({first.x.row(i).transpose(), {}, {}, 0, 0});
  }
  for (const auto& o : obs) noise.push_back(pooled_noise(replicate_groups(o)));
  for (auto& point : points) {
    for (size_t r = 0; r < obs.size(); ++r) {
      double sum = 0;
      int n = 0;
      for (int i = 0; i < obs[r].x.rows(); ++i)
        if (obs[r].x.row(i).transpose() == point.coded) sum += obs[r].y[i], ++n;
      point.runs = n;
      point.mean.push_back(sum / n);
      point.se.push_back(noise[r].known() ? noise[r].sd / std::sqrt(double(n)) : std::numeric_limits<double>::quiet_NaN());
      const PlanResponse& resp = plan.responses[size_t(obs[r].response)];
      point.miss += std::pow((point.mean.back() - resp.measured) / response_scale(resp), 2);
    }
  }
  return points;
}

// Position of a coded point along the path (0 at the first point, 1 at the last).
double along(const std::vector<PathPoint>& path, const Eigen::VectorXd& c) {
  const Eigen::VectorXd d = path.back().coded - path.front().coded;
  return (c - path.front().coded).dot(d) / d.squaredNorm();
}

void path_text(const CampaignPlan& plan, const std::vector<Observations>& obs, const CalibrationResult& res, size_t best,
               std::ostringstream& text) {
  text << "Steepest-ascent path: " << res.path.size() << " points, " << res.path.front().runs << " run(s) each; no model fitted.\n";
  for (size_t p = 0; p < res.path.size(); ++p) {
    text << "  " << p + 1 << ":";
    for (size_t j = 0; j < plan.factors.size(); ++j)
      text << " " << plan.factors[j].name << " = " << format_g(plan.factors[j].to_actual(res.path[p].coded[int(j)]), 5);
    for (size_t r = 0; r < obs.size(); ++r) {
      const PlanResponse& resp = plan.responses[size_t(obs[r].response)];
      text << ", " << resp.label << " " << format_g(res.path[p].mean[r], 5) << " +- " << format_g(res.path[p].se[r], 3) << " ("
           << (res.path[p].mean[r] >= resp.measured ? "+" : "") << format_g(100 * (res.path[p].mean[r] - resp.measured) / resp.measured, 3)
           << " %)";
    }
    text << (p == best ? "  <- chosen" : "") << "\n";
  }
  if (best > 0 && best + 1 < res.path.size()) {
    text << "A central composite design around the chosen point (its neighbours as -1 and +1):";
    for (size_t j = 0; j < plan.factors.size(); ++j) {
      const PlanFactor& f = plan.factors[j];
      text << " " << f.name << " " << format_g(f.to_actual(res.path[best - 1].coded[int(j)]), 5) << " .. "
           << format_g(f.to_actual(res.path[best + 1].coded[int(j)]), 5);
    }
    text << "\n";
  } else {
    text << "The chosen point is an end of the path: the measured value may lie beyond it; extend the path.\n";
  }
}

}  // namespace

CalibrationResult analyse_path(const CampaignPlan& plan, const std::vector<Observations>& obs) {
  CalibrationResult res;
  res.method = "steepest-ascent path";
  std::vector<NoiseEstimate> noise;
  res.path = path_points(plan, obs, noise);
  size_t best = 0;
  for (size_t p = 1; p < res.path.size(); ++p)
    if (res.path[p].miss < res.path[best].miss) best = p;
  res.chosen_coded = res.path[best].coded;
  res.chosen = to_actual(plan, res.chosen_coded);
  // For the figures: each response's path means joined by straight lines, read at a point's
  // position along the path.
  auto path = std::make_shared<std::vector<PathPoint>>(res.path);
  for (size_t r = 0; r < obs.size(); ++r) {
    ResponseModel m;
    m.response = obs[r].response;
    m.predict = [path, r](const Eigen::VectorXd& c) {
      const double t = std::clamp(along(*path, c), 0.0, 1.0) * double(path->size() - 1);
      const size_t i = std::min(size_t(t), path->size() - 2);
      return (*path)[i].mean[r] + (t - double(i)) * ((*path)[i + 1].mean[r] - (*path)[i].mean[r]);
    };
    m.noise = noise[r];
    m.runs = obs[r].runs;
    m.predicted = res.path[best].mean[r];
    m.predicted_sd = res.path[best].se[r];
    res.models.push_back(m);
  }
  res.model_on_target = within_tolerance(plan, res.models, res.chosen_coded);
  for (size_t j = 0; j < plan.factors.size(); ++j) {
    ParameterEstimate p;
    p.name = plan.factors[j].name;
    p.value = res.chosen[j];
    p.set_low = p.set_high = p.value;
    for (const auto& point : res.path)
      if (within_tolerance(plan, res.models, point.coded)) {
        p.set_low = std::min(p.set_low, plan.factors[j].to_actual(point.coded[int(j)]));
        p.set_high = std::max(p.set_high, plan.factors[j].to_actual(point.coded[int(j)]));
      }
    res.parameters.push_back(p);
  }
  std::ostringstream text;
  path_text(plan, obs, res, best, text);
  res.model_text = text.str();
  return res;
}

}  // namespace repose::calibrate
