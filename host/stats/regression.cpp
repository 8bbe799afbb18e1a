#include "stats/regression.h"

#include "stats/errors.h"

namespace repose::stats {

Eigen::MatrixXd model_matrix(const std::vector<Term>& terms, const Eigen::MatrixXd& x) {
  Eigen::MatrixXd X(x.rows(), static_cast<Eigen::Index>(terms.size()));
  std::vector<double> row(x.cols());
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    for (Eigen::Index j = 0; j < x.cols(); ++j) row[j] = x(i, j);
    for (size_t t = 0; t < terms.size(); ++t) X(i, static_cast<Eigen::Index>(t)) = term_value(terms[t], row.data());
  }
  return X;
}

LeastSquaresFit least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                              const std::vector<std::string>& names) {
  const Eigen::Index n = X.rows(), p = X.cols();
  if (n < p)
    throw ModelError("fewer runs (" + std::to_string(n) + ") than model terms (" +
                     std::to_string(p) + "): choose a smaller model or add runs");
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  // Relative threshold: a column whose remaining norm is below 1e-10 of the largest is aliased.
  qr.setThreshold(1e-10);
  if (qr.rank() < p) {
    std::string aliased;
    for (Eigen::Index j = qr.rank(); j < p; ++j) {
      Eigen::Index col = qr.colsPermutation().indices()(j);
      std::string name = col < static_cast<Eigen::Index>(names.size()) ? names[col]
                                                                       : "column " + std::to_string(col);
      aliased += (aliased.empty() ? "" : ", ") + name;
    }
    throw ModelError("the design cannot separate the model terms: " + aliased +
                     " aliased with other terms (rank " + std::to_string(qr.rank()) + " of " +
                     std::to_string(p) + ")");
  }
  LeastSquaresFit fit;
  fit.coef = qr.solve(y);
  fit.fitted = X * fit.coef;
  fit.residuals = y - fit.fitted;
  fit.sse = fit.residuals.squaredNorm();
  // Thin Q: leverage h_ii = |row i of Q|^2.
  Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(n, p);
  fit.leverage = q.rowwise().squaredNorm();
  // (X'X)^-1 = P R^-1 R^-T P^T.
  Eigen::MatrixXd r = qr.matrixR().topLeftCorner(p, p).triangularView<Eigen::Upper>();
  Eigen::MatrixXd rinv = r.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  Eigen::MatrixXd inner = rinv * rinv.transpose();
  Eigen::MatrixXd perm = qr.colsPermutation();
  fit.xtx_inverse = perm * inner * perm.transpose();
  return fit;
}

double residual_sum_of_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y) {
  if (X.cols() == 0) return y.squaredNorm();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  qr.setThreshold(1e-10);
  Eigen::VectorXd coef = qr.solve(y);
  return (y - X * coef).squaredNorm();
}

}  // namespace repose::stats
