#include "stats/dataset.h"

#include "stats/errors.h"

namespace repose::stats {

DataSet dataset_from_table(const Table& table, const std::vector<std::string>& factors,
                           const std::string& response, const std::vector<Factor>& ranges) {
  if (factors.empty()) throw TableError(table.source, 0, 0, "no factor columns given");
  if (!ranges.empty() && ranges.size() != factors.size())
    throw DesignError("one range per factor is needed: " + std::to_string(factors.size()) +
                      " factors, " + std::to_string(ranges.size()) + " ranges");
  for (const auto& r : ranges) check_range(r);
  DataSet d;
  d.response = response;
  d.factor_names = factors;
  d.ranges = ranges;
  for (size_t i = 0; i < factors.size(); ++i) {
    if (factors[i] == response)
      throw TableError(table.source, table.header_line, table.column_index(response) + 1,
                       "column '" + response + "' cannot be both a factor and the response");
    for (size_t j = 0; j < i; ++j)
      if (factors[j] == factors[i])
        throw TableError(table.source, table.header_line, table.column_index(factors[i]) + 1,
                         "factor column '" + factors[i] + "' is listed twice");
  }
  std::vector<int> cols;
  for (const auto& f : factors) cols.push_back(table.column_index(f));
  int ycol = table.column_index(response);
  if (table.rows() == 0) throw TableError(table.source, table.header_line, 0, "the table has no rows");
  d.coded.resize(table.rows(), static_cast<Eigen::Index>(factors.size()));
  d.y.resize(table.rows());
  for (int r = 0; r < table.rows(); ++r) {
    for (size_t j = 0; j < cols.size(); ++j) {
      double v = table.number(r, cols[j]);
      d.coded(r, static_cast<Eigen::Index>(j)) = ranges.empty() ? v : ranges[j].to_coded(v);
    }
    d.y(r) = table.number(r, ycol);
  }
  return d;
}

}  // namespace repose::stats
