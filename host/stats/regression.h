// Ordinary least squares for polynomial models in coded factors, solved by column-pivoting
// Householder QR (no normal equations, so near-collinear designs keep their accuracy).
#pragma once
#include <Eigen/Dense>
#include <vector>

#include "stats/model_terms.h"

namespace repose::stats {

// Columns = terms evaluated at each row of x (runs x factors, coded).
Eigen::MatrixXd model_matrix(const std::vector<Term>& terms, const Eigen::MatrixXd& x);

struct LeastSquaresFit {
  Eigen::VectorXd coef;       // one per model column
  Eigen::VectorXd fitted;     // X coef
  Eigen::VectorXd residuals;  // y - fitted
  Eigen::VectorXd leverage;   // diagonal of the hat matrix, for PRESS
  Eigen::MatrixXd xtx_inverse;  // (X'X)^-1, for coefficient standard errors
  double sse = 0;             // residual sum of squares
};

// Throws ModelError when there are fewer runs than columns, or when columns are aliased
// (the message names them via `names`, if given).
LeastSquaresFit least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                              const std::vector<std::string>& names = {});

// Residual sum of squares only (for extra-sum-of-squares tests); no rank check.
double residual_sum_of_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y);

}  // namespace repose::stats
