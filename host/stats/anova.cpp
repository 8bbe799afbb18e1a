#include "stats/anova.h"

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "stats/errors.h"
#include "stats/fdist.h"
#include "stats/regression.h"

namespace repose::stats {

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

AnovaRow tested_row(std::string source, double ss, int df, double mse, int df_error) {
  AnovaRow r{std::move(source), ss, df, df > 0 ? ss / df : kNaN, kNaN, kNaN};
  if (df > 0 && df_error > 0 && mse > 0) {
    r.f = r.ms / mse;
    r.p = f_upper_tail(r.f, df, df_error);
  }
  return r;
}

AnovaRow plain_row(std::string source, double ss, int df) {
  return AnovaRow{std::move(source), ss, df, df > 0 ? ss / df : kNaN, kNaN, kNaN};
}

Eigen::MatrixXd drop_column(const Eigen::MatrixXd& X, Eigen::Index col) {
  Eigen::MatrixXd out(X.rows(), X.cols() - 1);
  for (Eigen::Index j = 0, k = 0; j < X.cols(); ++j)
    if (j != col) out.col(k++) = X.col(j);
  return out;
}

// Pure error: the scatter of responses within groups of runs at the same design point.
// Points are matched after rounding the coded coordinates to 1e-6.
void pure_error(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, double& ss, int& df) {
  std::map<std::vector<long long>, std::vector<Eigen::Index>> groups;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    std::vector<long long> key(x.cols());
    for (Eigen::Index j = 0; j < x.cols(); ++j) key[j] = std::llround(x(i, j) * 1e6);
    groups[key].push_back(i);
  }
  ss = 0;
  df = 0;
  for (const auto& [key, rows] : groups) {
    if (rows.size() < 2) continue;
    double m = 0;
    for (auto i : rows) m += y(i);
    m /= static_cast<double>(rows.size());
    for (auto i : rows) ss += (y(i) - m) * (y(i) - m);
    df += static_cast<int>(rows.size()) - 1;
  }
}

}  // namespace

const AnovaRow& ResponseSurface::row(const std::string& source) const {
  if (model.source == source) return model;
  for (const auto& r : term_rows)
    if (r.source == source) return r;
  if (residual.source == source) return residual;
  if (lack_of_fit && lack_of_fit->source == source) return *lack_of_fit;
  if (pure_error && pure_error->source == source) return *pure_error;
  if (total.source == source) return total;
  throw std::out_of_range("no ANOVA row '" + source + "'");
}

double ResponseSurface::predict(const Eigen::VectorXd& coded) const {
  double v = 0;
  for (size_t t = 0; t < terms.size(); ++t) v += coef[static_cast<Eigen::Index>(t)] * term_value(terms[t], coded.data());
  return v;
}

Polynomial ResponseSurface::polynomial() const {
  Polynomial p;
  p.terms = terms;
  p.coef.assign(coef.data(), coef.data() + coef.size());
  return p;
}

namespace {

// The ANOVA table's rows: the model, each term (partial or sequential sums of squares), the
// residual split into lack of fit and pure error when replicates allow, the total.
void anova_rows(ResponseSurface& rs, const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const Eigen::MatrixXd& X,
                const std::vector<std::string>& names, double sst, double sse, double mse, SumOfSquaresType ss_type) {
  const int n = static_cast<int>(y.size());
  const int p = static_cast<int>(names.size());
  const int df_res = n - p;
  rs.model = tested_row("Model", sst - sse, p - 1, mse, df_res);
  // Per-term sums of squares: extra sum of squares of the term given the others (partial) or
  // given the terms before it (sequential).
  double prev_sse = sst;
  for (int t = 1; t < p; ++t) {
    double ss;
    if (ss_type == SumOfSquaresType::partial) {
      ss = residual_sum_of_squares(drop_column(X, t), y) - sse;
    } else {
      double s = residual_sum_of_squares(X.leftCols(t + 1), y);
      ss = prev_sse - s;
      prev_sse = s;
    }
    rs.term_rows.push_back(tested_row(names[t], std::max(ss, 0.0), 1, mse, df_res));
  }
  rs.residual = plain_row("Residual", sse, df_res);
  double ss_pe = 0;
  int df_pe = 0;
  pure_error(x, y, ss_pe, df_pe);
  int df_lof = df_res - df_pe;
  if (df_pe > 0 && df_lof > 0) {
    double ms_pe = ss_pe / df_pe;
    rs.lack_of_fit = tested_row("Lack of Fit", std::max(sse - ss_pe, 0.0), df_lof, ms_pe, df_pe);
    rs.pure_error = plain_row("Pure Error", ss_pe, df_pe);
  }
  rs.total = plain_row("Cor Total", sst, n - 1);
  rs.total.ms = kNaN;  // Design-Expert prints no mean square for the total
}

// Coefficient standard errors and variance inflation factors (VIF_j = 1 / (1 - R_j^2),
// R_j^2 from regressing column j on the other non-intercept columns).
std::vector<Coefficient> coefficients(const LeastSquaresFit& fit, const Eigen::MatrixXd& X,
                                      const std::vector<std::string>& names, double mse, int df_res) {
  std::vector<Coefficient> out;
  for (int t = 0; t < static_cast<int>(names.size()); ++t) {
    Coefficient c;
    c.term = names[t];
    c.estimate = fit.coef[t];
    c.std_error = df_res > 0 ? std::sqrt(mse * fit.xtx_inverse(t, t)) : kNaN;
    if (t > 0) {
      Eigen::VectorXd col = X.col(t);
      double centred = (col.array() - col.mean()).square().sum();
      double rss = residual_sum_of_squares(drop_column(X, t), col);
      c.vif = rss > 0 ? centred / rss : kNaN;
    }
    out.push_back(c);
  }
  return out;
}

// R^2, adjusted and predicted R^2 (PRESS), CV and Design-Expert's adequate precision.
FitStatistics fit_statistics(const LeastSquaresFit& fit, double mean, double sst, double sse, double mse, int n,
                             int p) {
  const int df_res = n - p;
  FitStatistics st;
  st.mean = mean;
  st.std_dev = std::sqrt(mse);
  st.cv_percent = 100.0 * st.std_dev / mean;
  st.r2 = sst > 0 ? 1.0 - sse / sst : kNaN;
  st.adj_r2 = (sst > 0 && df_res > 0) ? 1.0 - (sse / df_res) / (sst / (n - 1)) : kNaN;
  st.press = 0;
  for (int i = 0; i < n; ++i) {
    double one_minus_h = 1.0 - fit.leverage[i];
    if (one_minus_h < 1e-10) {
      st.press = kNaN;  // a run the model interpolates exactly: PRESS is undefined
      break;
    }
    double e = fit.residuals[i] / one_minus_h;
    st.press += e * e;
  }
  st.pred_r2 = sst > 0 ? 1.0 - st.press / sst : kNaN;
  // Design-Expert's Adeq Precision: the range of predicted values at the design points over
  // the average standard error of prediction, sqrt(mean V(y_hat)) = sqrt(p MSE / n).
  st.adeq_precision = (fit.fitted.maxCoeff() - fit.fitted.minCoeff()) / std::sqrt(p * mse / n);
  return st;
}

}  // namespace

ResponseSurface analyse(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                        const std::vector<Term>& terms, SumOfSquaresType ss_type) {
  if (terms.empty() || !terms[0].is_intercept())
    throw ModelError("the model must start with the intercept");
  if (x.rows() != y.size()) throw ModelError("design and response have different run counts");
  const int n = static_cast<int>(y.size());
  const int p = static_cast<int>(terms.size());
  std::vector<std::string> names;
  for (const auto& t : terms) names.push_back(term_name(t));
  Eigen::MatrixXd X = model_matrix(terms, x);
  LeastSquaresFit fit = least_squares(X, y, names);

  ResponseSurface rs;
  rs.factors = static_cast<int>(x.cols());
  rs.terms = terms;
  rs.coef = fit.coef;
  rs.ss_type = ss_type;
  rs.fitted = fit.fitted;
  rs.residuals = fit.residuals;
  rs.leverage = fit.leverage;
  rs.y_min = y.minCoeff();
  rs.y_max = y.maxCoeff();

  const double mean = y.mean();
  const double sst = (y.array() - mean).square().sum();
  const double sse = fit.sse;
  const int df_res = n - p;
  const double mse = df_res > 0 ? sse / df_res : kNaN;
  anova_rows(rs, x, y, X, names, sst, sse, mse, ss_type);
  rs.coefficients = coefficients(fit, X, names, mse, df_res);
  rs.stats = fit_statistics(fit, mean, sst, sse, mse, n, p);
  return rs;
}

Reduction reduce_backward(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                          std::vector<Term> terms, double alpha, bool keep_hierarchy,
                          SumOfSquaresType ss_type) {
  if (!(alpha > 0 && alpha < 1)) throw ModelError("the reduction alpha must lie in (0, 1)");
  Reduction red;
  for (;;) {
    ResponseSurface rs = analyse(x, y, terms, ss_type);
    int worst = -1;
    double worst_p = alpha;
    for (size_t t = 1; t < terms.size(); ++t) {
      if (keep_hierarchy) {
        bool needed = false;
        for (const auto& other : terms) needed = needed || terms[t].contained_in(other);
        if (needed) continue;
      }
      double p = rs.term_rows[t - 1].p;
      if (std::isnan(p)) continue;
      if (p > worst_p) {
        worst_p = p;
        worst = static_cast<int>(t);
      }
    }
    if (worst < 0) {
      red.model = std::move(rs);
      return red;
    }
    red.removed.push_back({term_name(terms[worst]), worst_p});
    terms.erase(terms.begin() + worst);
  }
}

}  // namespace repose::stats
