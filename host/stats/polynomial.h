// A fitted model as a polynomial: terms with coefficients, evaluated in coded units, converted
// to actual units (Design-Expert's "Final Equation in Terms of Actual Factors"), and printed.
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "stats/factor.h"
#include "stats/model_terms.h"

namespace repose::stats {

struct Polynomial {
  std::vector<Term> terms;
  std::vector<double> coef;

  int variables() const { return terms.empty() ? 0 : static_cast<int>(terms[0].powers.size()); }
  double operator()(const Eigen::VectorXd& x) const;
  double coefficient(const Term& t) const;  // 0 when the term is absent
};

// Substitutes coded = (actual - centre) / half_range into every term and collects the
// monomials of the actual variables. Terms absent from a non-hierarchical coded model can
// appear here (A^2 alone yields an A and a constant term).
Polynomial to_actual_units(const Polynomial& coded, const std::vector<Factor>& factors);

// "Y = 25.09 + 1.67 A - 0.32 AB + 1.84 A^2" with `names` for the variables (letters if empty).
std::string format_equation(const Polynomial& p, const std::string& response,
                            const std::vector<std::string>& names = {}, int significant = 4);

}  // namespace repose::stats
