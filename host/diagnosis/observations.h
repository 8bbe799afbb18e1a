// Measured data grouped the way the diagnosis compares it with simulation: conditions (one case
// with one set of overrides), and within a condition one group per measure (and time, for a
// series) holding the replicates. The replicate scatter gives the noise every residual is
// weighed against (pooled per measure: pure error), unless the file gives sigma.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "diagnosis/measured_data.h"

namespace repose {

struct Condition {
  std::string case_path;
  std::vector<CaseOverride> sets;
  std::string label;                        // "drop_height=0.3" (case stem when no overrides)
  std::map<std::string, double> variables;  // numeric set: values, by key
};

struct ObservationGroup {
  size_t condition = 0;
  std::string measure;
  bool series = false;
  double t = 0;                 // time within the series, s
  std::vector<double> values;   // the replicates
  double mean = 0;
  double sd = 0;                // noise of one value: given sigma, else the measure's pooled scatter
  double s2 = 0;                // sample variance of the replicates (n - 1 in the denominator)
  bool sigma_given = false;     // sd is the file's measurement error: the scatter itself is data
  int line = 0;                 // first CSV line of the group
  long previous = -1;           // series: the group at the previous t (same condition and measure)
  double weight() const { return double(values.size()) / (sd * sd); }  // 1 / var(mean)
};

struct NoiseEstimate {
  double sd = 0;   // pooled replicate standard deviation (or the given sigma)
  int df = 0;      // degrees of freedom of the pooled estimate (large when sigma is given)
  bool given = false;
  // A series (camera track): the lag-1 correlation of each replicate's deviations from the
  // replicate mean along t, pooled. Neighbouring frames of one track are not independent
  // measurements: the score whitens the series' residuals as AR(1) (model_fit.h) and the trend
  // tests and the noise's df count (1 + rho) / (1 - rho) frames as one.
  double lag1 = 0;
  double rho = 0;        // the correlation the score whitens the series with: lag1 in [0, 0.95]
  double inflation = 1;  // (1 + rho) / (1 - rho): how much a smooth deviation's noise is understated
};

struct Observations {
  std::string path;
  std::vector<Condition> conditions;
  std::vector<ObservationGroup> groups;
  std::map<std::string, NoiseEstimate> noise;  // by measure
  std::vector<std::string> variables;          // condition variables that vary
  std::vector<std::string> measures;           // in order of first appearance
  int noise_df() const;                        // the smallest df over the measures
};

// Throws DataError naming the file when a measure has neither replicates nor sigma.
Observations group_observations(const MeasuredData& data);

}  // namespace repose
