// Measured data for `repose diagnose` (README, "Measured data"): one CSV row per measured value,
// columns case, set:KEY..., measure, value, replicate, optional sigma and t. Reading checks every
// row against its case (the case loads with the row's overrides) and against the measure's units,
// and reports problems as FILE:LINE:COLUMN: column 'NAME': what is wrong.
#pragma once
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "case/case_loader.h"
#include "experiments/experiment.h"
#include "util/input_error.h"

namespace repose {

struct DataError : BadInput {  // bad input: exit code 2
  using BadInput::BadInput;
};

struct Measurement {
  std::string case_path;              // resolved against the CSV's folder
  std::vector<CaseOverride> sets;     // from the set:KEY columns, in column order
  std::string measure;                // e.g. rebound_height, height (a series with t)
  double value = 0;                   // SI units, angles in degrees
  int replicate = 0;
  std::optional<double> sigma;
  std::optional<double> t;            // time within a series, s
  int line = 0;                       // in the CSV
};

struct MeasuredData {
  std::string path;
  std::vector<Measurement> rows;
};

// Every measure the experiments diagnose simulates report: name, whether it is a time series, and
// its unit (experiments/registry.h).
const std::vector<MeasureInfo>& known_measures();
// A known measure's unit ("m", "deg", "1"); "" for an unknown one.
std::string unit_of(const std::string& measure);

// Throws DataError naming file, line and column.
MeasuredData read_measured_data(const std::string& path);

}  // namespace repose
