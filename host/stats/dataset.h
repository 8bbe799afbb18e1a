// The numbers a fit needs, taken from a CSV table: factor columns (coded, or actual values
// coded with given ranges) and a response column. Every failure names file, line and column.
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "stats/csv_table.h"
#include "stats/factor.h"

namespace repose::stats {

struct DataSet {
  std::string response;
  std::vector<std::string> factor_names;
  std::vector<Factor> ranges;  // actual range of each factor (coded -1..+1); empty when unknown
  Eigen::MatrixXd coded;       // runs x factors
  Eigen::VectorXd y;
};

// `ranges` empty: the factor columns hold coded values already. Otherwise one range per
// factor, and the columns hold actual values that are coded with it. Throws TableError for a
// missing column or a bad cell, DesignError for a reversed range.
DataSet dataset_from_table(const Table& table, const std::vector<std::string>& factors,
                           const std::string& response, const std::vector<Factor>& ranges = {});

// A fit of actual values as if they were coded is silently wrong (effects, p values and the
// "coded" equation all change), so columns must look coded unless ranges are given: symmetric
// about 0 (lowest = -highest) with a level at +-1 (every design's factorial or edge points).
// Throws StatsError naming the columns that do not, the NAME_coded columns to use instead when
// the table has them (as `repose design` writes), and the --coded ranges that would code them.
void require_coded_columns(const Table& table, const std::vector<std::string>& factors);

}  // namespace repose::stats
