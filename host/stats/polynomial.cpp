#include "stats/polynomial.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "stats/errors.h"

namespace repose::stats {

double Polynomial::operator()(const Eigen::VectorXd& x) const {
  double v = 0;
  for (size_t t = 0; t < terms.size(); ++t) v += coef[t] * term_value(terms[t], x.data());
  return v;
}

double Polynomial::coefficient(const Term& t) const {
  for (size_t i = 0; i < terms.size(); ++i)
    if (terms[i] == t) return coef[i];
  return 0;
}

Polynomial to_actual_units(const Polynomial& coded, const std::vector<Factor>& factors) {
  const int k = coded.variables();
  if (static_cast<int>(factors.size()) != k)
    throw ModelError("actual units need one range per factor (" + std::to_string(k) + "), got " +
                     std::to_string(factors.size()));
  for (const auto& f : factors) check_range(f);
  std::map<std::vector<int>, double> acc;
  for (size_t t = 0; t < coded.terms.size(); ++t) {
    // Product over factors of ((X - c) / h)^e = h^-e sum_m C(e, m) X^m (-c)^(e-m).
    std::map<std::vector<int>, double> partial{{std::vector<int>(k, 0), coded.coef[t]}};
    for (int i = 0; i < k; ++i) {
      int e = coded.terms[t].powers[i];
      if (e == 0) continue;
      double c = factors[i].centre(), h = factors[i].half_range();
      std::map<std::vector<int>, double> next;
      for (const auto& [powers, value] : partial) {
        double binom = 1;
        for (int m = 0; m <= e; ++m) {
          if (m > 0) binom = binom * (e - m + 1) / m;
          std::vector<int> q = powers;
          q[i] += m;
          next[q] += value * binom * std::pow(-c, e - m) / std::pow(h, e);
        }
      }
      partial.swap(next);
    }
    for (const auto& [powers, value] : partial) acc[powers] += value;
  }
  Polynomial out;
  for (const auto& [powers, value] : acc) {
    out.terms.push_back(Term{powers});
    out.coef.push_back(value);
  }
  // Present in Design-Expert's order.
  std::vector<size_t> idx(out.terms.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return out.terms[a] < out.terms[b]; });
  Polynomial sorted;
  for (size_t i : idx) {
    sorted.terms.push_back(out.terms[i]);
    sorted.coef.push_back(out.coef[i]);
  }
  return sorted;
}

std::string format_equation(const Polynomial& p, const std::string& response,
                            const std::vector<std::string>& names, int significant) {
  std::string s = response + " =";
  bool first = true;
  for (size_t t = 0; t < p.terms.size(); ++t) {
    double c = p.coef[t];
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", significant, std::fabs(c));
    if (first) {
      s += c < 0 ? " -" : " ";
      s += buf;
    } else {
      s += c < 0 ? " - " : " + ";
      s += buf;
    }
    first = false;
    if (!p.terms[t].is_intercept())
      s.append(names.empty() ? " " : " * ").append(names.empty() ? term_name(p.terms[t]) : term_name(p.terms[t], names));
  }
  if (first) s += " 0";
  return s;
}

}  // namespace repose::stats
