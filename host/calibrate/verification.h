// Whether the verification runs agree with the lab. The verification mean has a standard error
// (the run-to-run noise measured from replicates, over the runs' number), the measured value has
// one (the lab's sd over its replicate count); their difference d has
// se_d = sqrt(se_v^2 + se_m^2). The check is
//   confirmed     |d| <= tolerance and se_d <= tolerance: agreement, known to within the tolerance;
//   contradicted  |d| - 2 se_d > tolerance: the verification shows the tolerance is missed;
//   inconclusive  otherwise: the runs cannot tell (it says how many would).
// A campaign reaches its target only when every verified response is confirmed.
#pragma once
#include <string>
#include <vector>

#include "calibrate/noise.h"
#include "calibrate/plan.h"
#include "calibrate/run_spec.h"

namespace repose::calibrate {

enum class Agreement { confirmed, inconclusive, contradicted, not_run };
const char* agreement_name(Agreement a);

struct ResponseCheck {
  int response = 0;                 // index into plan.responses
  std::vector<RunRecord> runs;      // at the calibrated point
  double mean = 0, run_sd = 0;      // of the runs (run_sd: their own sample sd)
  NoiseEstimate noise;              // the response's run-to-run noise, pooled over every replicate group
  double se = 0;                    // of the mean: noise sd / sqrt(runs); NaN when the noise is unknown
  double measured_se = 0;
  double difference = 0, difference_se = 0;  // mean - measured, and its standard error
  double tolerance = 0;             // absolute
  Agreement agreement = Agreement::not_run;
  // Verification runs that would bring se_d within the tolerance at this noise (-1: none can,
  // the lab's own standard error exceeds it; 0: the noise is unknown).
  int runs_needed = 0;

  double relative_error(double measured) const { return difference / measured; }
};

// Judges the verification runs of one response. `noise` pools every replicate group of the
// response (the verification runs included); with no replicates, the runs' own sd is used when
// there are two or more.
ResponseCheck check_response(const CampaignPlan& plan, int response, const std::vector<RunRecord>& runs,
                             const NoiseEstimate& noise);

// One line: "angle: 19.91 +- 1.2 (3 runs) against 17.56 +- 0: difference +2.35 +- 1.2, tolerance
// 0.18: contradicted".
std::string check_text(const CampaignPlan& plan, const ResponseCheck& check);

}  // namespace repose::calibrate
