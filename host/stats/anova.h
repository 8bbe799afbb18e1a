// Analysis of variance of a polynomial model fitted by least squares, laid out as
// Design-Expert prints it: Model, one row per term, Residual split into Lack of Fit and Pure
// Error (replicated design points), Cor Total; then Std. Dev., Mean, C.V. %, PRESS, R^2,
// adjusted and predicted R^2 and Adeq Precision. Per-term sums of squares are partial
// (Type III: each term adjusted for all the others), Design-Expert's default; sequential
// (Type I) is available for comparison.
#pragma once
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "stats/model_terms.h"
#include "stats/polynomial.h"

namespace repose::stats {

enum class SumOfSquaresType { partial, sequential };

struct AnovaRow {
  std::string source;
  double ss = 0;
  int df = 0;
  double ms = 0;
  double f = 0;  // NaN where no F test applies (Residual, Pure Error, Cor Total)
  double p = 0;  // NaN where no F test applies
};

struct FitStatistics {
  double std_dev = 0;        // sqrt(residual mean square)
  double mean = 0;           // of the response
  double cv_percent = 0;     // 100 std_dev / mean
  double press = 0;          // sum (e_i / (1 - h_ii))^2; NaN if a run has leverage 1
  double r2 = 0;
  double adj_r2 = 0;
  double pred_r2 = 0;        // 1 - PRESS / SS_total
  double adeq_precision = 0; // range of predictions at the design points / sqrt(p MSE / n)
};

struct Coefficient {
  std::string term;   // "A", "AB", "A^2", "Intercept"
  double estimate = 0;
  double std_error = 0;
  double vif = 0;     // variance inflation factor (1 for orthogonal terms; 0 for the intercept)
};

struct ResponseSurface {
  int factors = 0;
  std::vector<Term> terms;     // intercept first
  Eigen::VectorXd coef;        // coded units, one per term
  std::vector<Coefficient> coefficients;
  SumOfSquaresType ss_type = SumOfSquaresType::partial;
  AnovaRow model;
  std::vector<AnovaRow> term_rows;  // one per non-intercept term, in model order
  AnovaRow residual;
  std::optional<AnovaRow> lack_of_fit;  // present when there are replicates and spare df
  std::optional<AnovaRow> pure_error;
  AnovaRow total;                   // corrected total
  FitStatistics stats;
  Eigen::VectorXd fitted, residuals, leverage;
  double y_min = 0, y_max = 0;      // observed response range

  const AnovaRow& row(const std::string& source) const;  // throws std::out_of_range
  double predict(const Eigen::VectorXd& coded) const;
  Polynomial polynomial() const;  // the coded-unit equation
};

// x: runs x factors (coded), y: response. Throws ModelError when the model cannot be fitted.
ResponseSurface analyse(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                        const std::vector<Term>& terms,
                        SumOfSquaresType ss_type = SumOfSquaresType::partial);

struct RemovedTerm {
  std::string term;
  double p = 0;  // its p value in the model it was removed from
};

struct Reduction {
  ResponseSurface model;
  std::vector<RemovedTerm> removed;  // in the order they were dropped
};

// Backward elimination: refit, drop the term with the largest p value above alpha, repeat.
// With keep_hierarchy, a term is only a candidate while no remaining term contains it
// (A stays while AB or A^2 stays), as Design-Expert does for hierarchical models.
Reduction reduce_backward(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                          std::vector<Term> terms, double alpha, bool keep_hierarchy = true,
                          SumOfSquaresType ss_type = SumOfSquaresType::partial);

}  // namespace repose::stats
