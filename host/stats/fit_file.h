// A fitted model saved as JSON by `repose fit --json` and read back by `repose optimize`:
// the factors and their coding, the coded equation, the region the data covered, the ANOVA and
// the fit statistics.
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "stats/anova.h"
#include "stats/dataset.h"
#include "stats/json.h"
#include "stats/polynomial.h"

namespace repose::stats {

struct SavedFit {
  std::string source;                 // the fit file's path (for messages)
  std::string response;
  std::vector<std::string> factor_names;
  std::vector<Factor> ranges;         // empty when the fit was made on coded columns only
  Polynomial coded;                   // equation in coded units
  Eigen::VectorXd coded_min, coded_max;  // region covered by the design
  double y_min = 0, y_max = 0;        // observed response range
};

Json fit_to_json(const ResponseSurface& fit, const DataSet& data, const std::string& table_source,
                 const std::string& model_name, const std::vector<RemovedTerm>& removed);

// Throws InputError naming the file, line and column of a missing or malformed entry.
SavedFit saved_fit_from_json(const Json& j);
SavedFit read_fit_file(const std::string& path);

}  // namespace repose::stats
