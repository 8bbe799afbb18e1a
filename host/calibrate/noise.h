// Run-to-run noise measured from replicates: runs at the same parameters that differ only by
// their packing seed (a pilot, centre points, repeats of the loop, the verification). Pooled over
// the groups, with its chi-square confidence interval, so a report says how well the noise itself
// is known; nothing assumes it.
#pragma once
#include <vector>

namespace repose::calibrate {

struct NoiseEstimate {
  double sd = 0;   // pooled sd of one run
  int df = 0;      // degrees of freedom: sum over groups of (size - 1); 0 when nothing is replicated
  double low = 0, high = 0;  // 95 % confidence interval of the sd (high is infinite without replicates)
  bool known() const { return df > 0; }
};

// Pooled over groups of replicate responses (groups of one add nothing). Deviations are taken
// from each group's first value, so identical replicates give exactly zero.
NoiseEstimate pooled_noise(const std::vector<std::vector<double>>& groups);

// Two estimates pooled (their sums of squares and degrees of freedom added).
NoiseEstimate combine(const NoiseEstimate& a, const NoiseEstimate& b);

// The 95 % confidence interval of a standard deviation `sd` estimated on `df` degrees of freedom:
// sqrt(df sd^2 / chi2(0.975, df)) .. sqrt(df sd^2 / chi2(0.025, df)).
void sd_interval(double sd, int df, double& low, double& high);

// Runs at one point whose mean has standard error `se` at noise `sd`: ceil((sd / se)^2), at least 1.
int runs_for_standard_error(double sd, double se);

}  // namespace repose::calibrate
