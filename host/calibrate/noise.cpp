#include "calibrate/noise.h"

#include <cmath>
#include <limits>

#include "stats/fdist.h"

namespace repose::calibrate {

void sd_interval(double sd, int df, double& low, double& high) {
  if (df <= 0) {
    low = 0;
    high = std::numeric_limits<double>::infinity();
    return;
  }
  const double ss = df * sd * sd;
  low = std::sqrt(ss / stats::chi_square_quantile(0.975, df));
  high = std::sqrt(ss / stats::chi_square_quantile(0.025, df));
}

NoiseEstimate pooled_noise(const std::vector<std::vector<double>>& groups) {
  NoiseEstimate n;
  double ss = 0;
  for (const auto& g : groups) {
    if (g.size() < 2) continue;
    double m = 0;
    for (double v : g) m += v - g[0];
    m /= double(g.size());
    for (double v : g) ss += (v - g[0] - m) * (v - g[0] - m);
    n.df += int(g.size()) - 1;
  }
  n.sd = n.df > 0 ? std::sqrt(ss / n.df) : 0;
  sd_interval(n.sd, n.df, n.low, n.high);
  return n;
}

NoiseEstimate combine(const NoiseEstimate& a, const NoiseEstimate& b) {
  NoiseEstimate n;
  n.df = a.df + b.df;
  n.sd = n.df > 0 ? std::sqrt((a.df * a.sd * a.sd + b.df * b.sd * b.sd) / n.df) : 0;
  sd_interval(n.sd, n.df, n.low, n.high);
  return n;
}

int runs_for_standard_error(double sd, double se) {
  if (!(se > 0)) return std::numeric_limits<int>::max();
  const double n = std::ceil((sd / se) * (sd / se) - 1e-9);
  return n > 1e9 ? std::numeric_limits<int>::max() : std::max(1, int(n));
}

}  // namespace repose::calibrate
