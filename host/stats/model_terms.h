// Polynomial model terms over k coded factors: the intercept, main effects (A), interactions
// (AB), and powers (A^2). A term is a vector of exponents, one per factor, which makes
// hierarchy ("A is contained in AB") and actual-unit expansion plain arithmetic.
#pragma once
#include <string>
#include <vector>

namespace repose::stats {

struct Term {
  std::vector<int> powers;  // exponent of each factor; all zero = intercept

  int order() const;              // total degree
  bool is_intercept() const { return order() == 0; }
  // True when this term's monomial divides `other` and differs from it (A in AB, A in A^2).
  bool contained_in(const Term& other) const;
  bool operator==(const Term& o) const { return powers == o.powers; }
  bool operator<(const Term& o) const;  // Design-Expert's order: degree, then factor order
};

enum class ModelKind { mean, linear, interaction, quadratic, cubic };

ModelKind parse_model_kind(const std::string& s);  // "linear", "interaction"/"2fi", "quadratic", ...
std::string model_kind_name(ModelKind kind);

// Intercept first, then terms in Design-Expert's order: A, B, C, AB, AC, BC, A^2, B^2, C^2.
std::vector<Term> build_model(ModelKind kind, int factors);

// The letter Design-Expert gives factor i: A, B, ..., H, J, ... (I is skipped: it denotes the
// identity in defining relations of fractional factorials).
std::string factor_letter(int i);
int factor_from_letter(char c);  // -1 when c is not a factor letter

// "A", "AB", "A^2", "A^2B", "Intercept".
std::string term_name(const Term& t);
// The same with factor names: "mu_s", "mu_s*mu_r", "mu_s^2".
std::string term_name(const Term& t, const std::vector<std::string>& names);
// Parses a name such as "AB" or "A^2" back into a term over k factors; throws ModelError.
Term parse_term(const std::string& name, int factors);

// A model is hierarchical when every term's lower-order constituents are in the model too.
bool is_hierarchical(const std::vector<Term>& terms);

// Value of a term at a coded point.
double term_value(const Term& t, const double* x);

}  // namespace repose::stats
