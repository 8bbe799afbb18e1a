#include "calibrate/calibration_result.h"

#include <cmath>
#include <cstdio>

#include "calibrate/adaptive_loop.h"
#include "calibrate/plan.h"

namespace repose::calibrate {

double response_scale(const PlanResponse& r) { return r.measured_se() > 0 ? r.measured_se() : r.absolute_tolerance(); }

double expected_miss(const CampaignPlan& plan, const std::vector<ResponseModel>& models, const Eigen::VectorXd& coded) {
  double j = 0;
  for (const auto& m : models) {
    const PlanResponse& r = plan.responses[size_t(m.response)];
    const double d = m.predict(coded) - r.measured, s = m.predict_sd ? m.predict_sd(coded) : 0.0, u = response_scale(r);
    j += (d * d + s * s) / (u * u);
  }
  return j;
}

bool within_tolerance(const CampaignPlan& plan, const std::vector<ResponseModel>& models, const Eigen::VectorXd& coded) {
  for (const auto& m : models) {
    const PlanResponse& r = plan.responses[size_t(m.response)];
    if (!(std::abs(m.predict(coded) - r.measured) <= r.absolute_tolerance())) return false;
  }
  return true;
}

std::vector<std::pair<int, double>> held_factors(const CampaignPlan& plan) {
  std::vector<std::pair<int, double>> held;
  for (auto [j, v] : plan.design.fixed) held.push_back({j, plan.factors[size_t(j)].to_coded(v)});
  return held;
}

void describe_parameters(const CampaignPlan& plan, CalibrationResult& res) {
  const int k = int(plan.factors.size());
  const auto held = held_factors(plan);
  Eigen::VectorXd lo = res.chosen_coded, hi = res.chosen_coded;
  for (auto p : halton_points(k, 1, 4096)) {
    for (auto [j, v] : held) p[j] = v;
    if (within_tolerance(plan, res.models, p)) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  res.chosen = to_actual(plan, res.chosen_coded);
  res.parameters.clear();
  const auto& predict = res.primary().predict;
  for (int j = 0; j < k; ++j) {
    const PlanFactor& f = plan.factors[size_t(j)];
    Eigen::VectorXd a = res.chosen_coded, b = res.chosen_coded;
    a[j] += 1e-4;
    b[j] -= 1e-4;
    ParameterEstimate p;
    p.name = f.name;
    p.value = res.chosen[size_t(j)];
    p.slope = (predict(a) - predict(b)) / 2e-4 / (0.5 * (f.high - f.low));
    p.set_low = f.to_actual(lo[j]);
    p.set_high = f.to_actual(hi[j]);
    res.parameters.push_back(p);
  }
}

void add_posterior(const CampaignPlan& plan, CalibrationResult& res) {
  std::vector<PosteriorInput> inputs;
  for (const auto& m : res.models) {
    const PlanResponse& r = plan.responses[size_t(m.response)];
    inputs.push_back({m.predict, m.predict_sd, r.measured, r.measured_se()});
  }
  res.posterior = compute_posterior(int(plan.factors.size()), inputs, held_factors(plan));
  const Posterior& post = res.posterior;
  for (size_t j = 0; j < res.parameters.size(); ++j) {
    const PlanFactor& f = plan.factors[j];
    const CredibleInterval& c = post.marginal[j];
    ParameterEstimate& p = res.parameters[j];
    p.has_posterior = true;
    p.low = f.to_actual(c.low);
    p.median = f.to_actual(c.median);
    p.high = f.to_actual(c.high);
    p.sd = c.sd * 0.5 * (f.high - f.low);
    p.identified = c.high - c.low < 0.8 * 2.0;
  }
  res.ridge_text.clear();
  if (post.free.size() < 2) return;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "The posterior extends most along %s (coded units): sd %.3g along it, %.3g across it; a flat prior has %.3g. ",
                direction_text(post.ridge, plan.factor_names()).c_str(), post.ridge_sd, post.across_sd, kFlatPriorSd);
  res.ridge_text = buf;
  int axis = 0;
  for (int j = 1; j < post.ridge.size(); ++j)
    if (std::abs(post.ridge[j]) > std::abs(post.ridge[axis])) axis = j;
  if (post.ridge_sd > 0.5 * kFlatPriorSd && post.across_sd < 0.5 * post.ridge_sd && std::abs(post.ridge[axis]) > 0.95)
    res.ridge_text += "The data leave " + plan.factors[size_t(axis)].name +
                      " free: the measured response hardly depends on it (not identifiable from this response).";
  else if (post.ridge_sd > 0.5 * kFlatPriorSd && post.across_sd < 0.5 * post.ridge_sd)
    res.ridge_text += "The measurement fixes a combination of the parameters, not each one: along this ridge the data "
                      "leave them free (not identifiable from this response).";
  else if (post.ridge_sd > 0.5 * kFlatPriorSd)
    res.ridge_text += "The data leave the parameters nearly as free as the prior: they are not identified.";
  else
    res.ridge_text += "The data pin the parameters down in every direction.";
}

}  // namespace repose::calibrate
