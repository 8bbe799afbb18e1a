#include "stats/model_terms.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "stats/errors.h"

namespace repose::stats {

int Term::order() const {
  int s = 0;
  for (int p : powers) s += p;
  return s;
}

bool Term::contained_in(const Term& other) const {
  if (powers.size() != other.powers.size() || powers == other.powers) return false;
  for (size_t i = 0; i < powers.size(); ++i)
    if (powers[i] > other.powers[i]) return false;
  return true;
}

// Degree first; within a degree, pure interactions (all exponents 1) before powers, as in
// Design-Expert's listing (AB, AC, BC, A^2, B^2, C^2); then lexicographic on the factors.
bool Term::operator<(const Term& o) const {
  if (order() != o.order()) return order() < o.order();
  int max_a = powers.empty() ? 0 : *std::max_element(powers.begin(), powers.end());
  int max_b = o.powers.empty() ? 0 : *std::max_element(o.powers.begin(), o.powers.end());
  if (max_a != max_b) return max_a < max_b;
  return powers > o.powers;  // A (1,0,..) before B (0,1,..)
}

ModelKind parse_model_kind(const std::string& s) {
  if (s == "mean") return ModelKind::mean;
  if (s == "linear" || s == "main") return ModelKind::linear;
  if (s == "interaction" || s == "2fi") return ModelKind::interaction;
  if (s == "quadratic") return ModelKind::quadratic;
  if (s == "cubic") return ModelKind::cubic;
  throw ModelError("unknown model '" + s + "' (use linear, interaction, quadratic or cubic)");
}

std::string model_kind_name(ModelKind kind) {
  switch (kind) {
    case ModelKind::mean: return "mean";
    case ModelKind::linear: return "linear";
    case ModelKind::interaction: return "interaction";
    case ModelKind::quadratic: return "quadratic";
    case ModelKind::cubic: return "cubic";
  }
  return "?";
}

std::vector<Term> build_model(ModelKind kind, int k) {
  std::vector<Term> terms;
  terms.push_back(Term{std::vector<int>(k, 0)});
  int degree = kind == ModelKind::mean ? 0 : kind == ModelKind::linear ? 1
             : kind == ModelKind::cubic ? 3 : 2;
  // Enumerate all monomials up to the degree, then keep those the model kind admits.
  std::vector<Term> all;
  std::vector<int> p(k, 0);
  auto rec = [&](auto&& self, int i, int left) -> void {
    if (i == k) {
      Term t{p};
      if (t.order() > 0) all.push_back(t);
      return;
    }
    for (int e = 0; e <= left; ++e) {
      p[i] = e;
      self(self, i + 1, left - e);
    }
    p[i] = 0;
  };
  rec(rec, 0, degree);
  for (const auto& t : all) {
    int max_p = *std::max_element(t.powers.begin(), t.powers.end());
    bool keep = kind == ModelKind::linear ? t.order() == 1
              : kind == ModelKind::interaction ? max_p == 1
              : true;  // quadratic and cubic keep every monomial up to their degree
    if (keep) terms.push_back(t);
  }
  std::sort(terms.begin() + 1, terms.end());
  return terms;
}

std::string factor_letter(int i) {
  if (i < 0 || i >= 25) throw ModelError("at most 25 factors have letters (A..Z without I)");
  char c = static_cast<char>('A' + i + (i >= 8 ? 1 : 0));
  return std::string(1, c);
}

int factor_from_letter(char c) {
  c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (c < 'A' || c > 'Z' || c == 'I') return -1;
  return c - 'A' - (c > 'I' ? 1 : 0);
}

std::string term_name(const Term& t) {
  if (t.is_intercept()) return "Intercept";
  std::string s;
  for (size_t i = 0; i < t.powers.size(); ++i) {
    if (t.powers[i] == 0) continue;
    s += factor_letter(static_cast<int>(i));
    if (t.powers[i] > 1) s.append("^").append(std::to_string(t.powers[i]));
  }
  return s;
}

std::string term_name(const Term& t, const std::vector<std::string>& names) {
  if (t.is_intercept()) return "Intercept";
  std::string s;
  for (size_t i = 0; i < t.powers.size(); ++i) {
    if (t.powers[i] == 0) continue;
    if (!s.empty()) s += "*";
    s += names.at(i);
    if (t.powers[i] > 1) s.append("^").append(std::to_string(t.powers[i]));
  }
  return s;
}

Term parse_term(const std::string& name, int k) {
  Term t{std::vector<int>(k, 0)};
  if (name == "Intercept" || name == "1") return t;
  size_t i = 0;
  while (i < name.size()) {
    int f = factor_from_letter(name[i]);
    if (f < 0 || f >= k) throw ModelError("term '" + name + "': '" + name[i] + "' is not a factor");
    ++i;
    int power = 1;
    if (i < name.size() && name[i] == '^') {
      size_t j = ++i;
      while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i]))) ++i;
      if (i == j) throw ModelError("term '" + name + "': missing exponent after '^'");
      power = std::stoi(name.substr(j, i - j));
    }
    t.powers[f] += power;
  }
  return t;
}

bool is_hierarchical(const std::vector<Term>& terms) {
  for (const auto& t : terms) {
    // Every term obtained by lowering one exponent by one must be present.
    for (size_t i = 0; i < t.powers.size(); ++i) {
      if (t.powers[i] == 0) continue;
      Term lower = t;
      --lower.powers[i];
      if (std::find(terms.begin(), terms.end(), lower) == terms.end()) return false;
    }
  }
  return true;
}

double term_value(const Term& t, const double* x) {
  double v = 1.0;
  for (size_t i = 0; i < t.powers.size(); ++i)
    for (int e = 0; e < t.powers[i]; ++e) v *= x[i];
  return v;
}

}  // namespace repose::stats
