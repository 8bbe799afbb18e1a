// The score a model's free parameters are fitted by (on its surrogate, surrogate.h, in the unit
// cube of the parameters' search ranges, log ranges for strengths spanning decades):
//   chi^2 = sum over groups of (mean - predicted)^2 / (V/n + v/R)
//         + sum over groups with n >= 2, when the file gives sigma, of (n-1) [s^2/V - 1 - ln(s^2/V)]
// with n replicates measured, s^2 their sample variance, v the model's replicate variance from R
// simulated replicates (0 for a deterministic model) and V the variance of one measured value:
// sigma^2 + v when sigma is given, else the pooled replicate scatter (which then holds any
// scatter the body itself causes). The second sum is the deviance of s^2 against V ((n-1) s^2/V
// is chi^2 with n-1 degrees of freedom): a model that predicts the wrong scatter pays for it,
// one chi^2 term per group. A series' mean terms are whitened as AR(1) with the correlation
// its tracks show (observations.h): z = residual / its SD, w = (z_t - rho z_prev) / sqrt(1 - rho^2)
// (the first point unchanged), so that correlated frames count as the independent information
// they hold (a generalised least-squares score; rho = 0 leaves it as above).
#pragma once
#include <vector>

#include "diagnosis/predictor.h"

namespace repose {

// Every group's terms of the score (above): against the measured means and scatter or, when
// `target` is given, against another model's prediction as if it were the truth (mean, and
// sample variance sd^2 + its replicate variance).
std::vector<double> group_chi_squares(const Observations& obs, const Prediction& predicted,
                                      const Prediction* target = nullptr);
// The score over the groups of the conditions marked in `use`.
double chi_square(const Observations& obs, const Prediction& predicted, const std::vector<char>& use,
                  const Prediction* target = nullptr);
// A stochastic model's predicted change from the baseline, d = candidate - baseline per group, is
// the difference of two Monte-Carlo means: for a chaotic simulation (a heap) any parameter change
// redraws every fill's outcome, so d carries the scatter of both (var_d = vb/Rb + vc/Rc) even
// where the change does nothing. Its estimate is shrunk toward no change by the positive-part
// James-Stein factor s = max(0, 1 - (G - 2) / D), D = sum d^2 / var_d over the G groups (James &
// Stein 1961: for G >= 3 it estimates the vector of changes better than d itself): a change no
// larger than the simulations' scatter (D ~ G) becomes none, a real one (D >> G) stays. The
// shrunk model predicts the means baseline + s d, with variance (1 - s)^2 vb/Rb + s^2 vc/Rc, and
// the candidate's own replicate scatter vc (a scatter between the two models' is no model's). G counts the groups whose means scatter; a
// deterministic pair (var_d = 0 everywhere) or fewer than 3 such groups are left as they are (s = 1).
struct ShrunkChange {
  Prediction prediction;
  double shrinkage = 1;  // s
  double d2 = 0;         // D
};
ShrunkChange shrink_change(const Observations& obs, const Prediction& baseline, const Prediction& candidate);
// How many chi^2 terms the score has over all groups: one per mean, plus one per replicate
// variance when sigma is given (the degrees of freedom before fitting).
int score_terms(const Observations& obs);

}  // namespace repose
