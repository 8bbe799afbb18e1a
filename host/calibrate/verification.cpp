#include "calibrate/verification.h"

#include <cmath>
#include <limits>

#include "calibrate/observations.h"
#include "util/number_text.h"

namespace repose::calibrate {

const char* agreement_name(Agreement a) {
  switch (a) {
    case Agreement::confirmed: return "confirmed";
    case Agreement::inconclusive: return "inconclusive";
    case Agreement::contradicted: return "contradicted";
    case Agreement::not_run: return "not run";
  }
  return "?";
}

ResponseCheck check_response(const CampaignPlan& plan, int response, const std::vector<RunRecord>& runs,
                             const NoiseEstimate& noise) {
  const PlanResponse& r = plan.responses.at(size_t(response));
  ResponseCheck c;
  c.response = response;
  c.runs = runs;
  c.measured_se = r.measured_se();
  c.tolerance = r.absolute_tolerance();
  if (runs.empty()) return c;
  std::vector<double> v;
  for (const auto& run : runs) v.push_back(response_value(run, r.name));
  const NoiseEstimate own = pooled_noise({v});
  double shift = 0;
  for (double e : v) shift += e - v[0];
  c.mean = v[0] + shift / double(v.size());
  c.run_sd = own.sd;
  c.noise = noise.known() ? noise : own;
  const double n = double(v.size());
  c.se = c.noise.known() ? c.noise.sd / std::sqrt(n) : std::numeric_limits<double>::quiet_NaN();
  c.difference = c.mean - r.measured;
  c.difference_se = std::hypot(c.se, c.measured_se);
  if (!c.noise.known()) {
    c.agreement = Agreement::inconclusive;  // one run and no replicates: no standard error
  } else if (std::abs(c.difference) <= c.tolerance && c.difference_se <= c.tolerance) {
    c.agreement = Agreement::confirmed;
  } else if (std::abs(c.difference) - 2 * c.difference_se > c.tolerance) {
    c.agreement = Agreement::contradicted;
  } else {
    c.agreement = Agreement::inconclusive;
  }
  if (c.measured_se >= c.tolerance) c.runs_needed = -1;
  else if (c.noise.known())
    c.runs_needed = runs_for_standard_error(c.noise.sd, std::sqrt(c.tolerance * c.tolerance - c.measured_se * c.measured_se));
  return c;
}

std::string check_text(const CampaignPlan& plan, const ResponseCheck& c) {
  const PlanResponse& r = plan.responses.at(size_t(c.response));
  auto g = [](double v) { return std::isfinite(v) ? format_g(v, 4) : std::string("unknown"); };
  std::string s = r.label + ": " + g(c.mean) + " +- " + g(c.se) + " (" + std::to_string(c.runs.size()) + " run" +
                  (c.runs.size() == 1 ? "" : "s") + ") against measured " + g(r.measured) + " +- " + g(c.measured_se) +
                  ": difference " + (c.difference >= 0 ? "+" : "") + g(c.difference) + " +- " + g(c.difference_se) +
                  ", tolerance " + g(c.tolerance) + ": " + agreement_name(c.agreement);
  if (c.agreement != Agreement::confirmed) {
    if (c.runs_needed < 0)
      s += " (the lab's own standard error " + g(c.measured_se) + " exceeds the tolerance: no number of runs can confirm it)";
    else if (c.runs_needed > 0 && c.difference_se > c.tolerance)
      s += " (at noise sd " + g(c.noise.sd) + ", " + std::to_string(c.runs_needed) + " runs would know the mean to the tolerance)";
  }
  return s;
}

}  // namespace repose::calibrate
