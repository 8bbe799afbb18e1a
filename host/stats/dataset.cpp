#include "stats/dataset.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "stats/errors.h"

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

namespace {

bool looks_coded(const std::vector<double>& v) {
  double lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
  bool symmetric = std::fabs(lo + hi) <= 1e-6 * std::max(1.0, hi);
  bool unit_level = std::any_of(v.begin(), v.end(), [](double x) { return std::fabs(std::fabs(x) - 1) < 1e-6; });
  return hi > 0 && symmetric && unit_level;
}

// "LOW:HIGH" of an actual column from its NAME_coded twin: the values at coded -1 and +1.
std::string range_from_twin(const std::vector<double>& actual, const std::vector<double>& coded) {
  for (size_t a = 0; a < coded.size(); ++a)
    for (size_t b = 0; b < coded.size(); ++b)
      if (coded[b] - coded[a] > 1e-9) {
        double slope = (actual[b] - actual[a]) / (coded[b] - coded[a]);
        double centre = actual[a] - slope * coded[a];
        std::ostringstream r;
        r << std::setprecision(10) << centre - slope << ":" << centre + slope;
        return r.str();
      }
  return "";
}

}  // namespace

void require_coded_columns(const Table& table, const std::vector<std::string>& factors) {
  std::vector<std::string> actual, twins, ranges;
  for (const auto& f : factors) {
    auto v = table.numeric_column(f);
    if (v.empty() || looks_coded(v)) continue;
    double lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
    std::ostringstream what;
    what << f << " (" << lo << " .. " << hi << ")";
    actual.push_back(what.str());
    std::string twin = f + "_coded";
    if (table.has_column(twin)) {
      twins.push_back(twin);
      ranges.push_back(range_from_twin(v, table.numeric_column(twin)));
    }
  }
  if (actual.empty()) return;
  auto join = [](const std::vector<std::string>& items, const char* separator = ",") {
    std::string s;
    for (const auto& i : items) s += (s.empty() ? "" : separator) + i;
    return s;
  };
  std::string message = table.source + ": the factor columns " + join(actual, ", ") +
                        " are not coded (coded columns run symmetric about 0 with levels at +-1): fitting actual values "
                        "as coded ones gives wrong effects and p values. ";
  if (twins.size() == actual.size())
    message += "Fit the coded columns (--factors " + join(twins) + "), or code these with --coded " + join(ranges);
  else
    message += "Give --coded LOW:HIGH per factor (the actual values at coded -1 and +1), or --ranges if they are coded";
  throw StatsError(message);
}

}  // namespace repose::stats
