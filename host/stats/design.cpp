#include "stats/design.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "stats/errors.h"
#include "stats/model_terms.h"
#include "util/number_text.h"

namespace repose::stats {

namespace {

void check_factors(const std::vector<Factor>& factors, int min_k, int max_k, const char* what) {
  int k = static_cast<int>(factors.size());
  if (k < min_k || k > max_k)
    throw DesignError(std::string(what) + " needs " + std::to_string(min_k) + " to " +
                      std::to_string(max_k) + " factors, got " + std::to_string(k));
  for (size_t i = 0; i < factors.size(); ++i) {
    check_range(factors[i]);
    for (size_t j = 0; j < i; ++j)
      if (factors[j].name == factors[i].name)
        throw DesignError("factor '" + factors[i].name + "' is given twice");
  }
}

void check_centres(int centres) {
  if (centres < 0) throw DesignError("the number of centre points cannot be negative");
}

// Appends `centres` all-zero runs.
void add_centres(Design& d, int centres) {
  check_centres(centres);
  int n = d.runs();
  d.coded.conservativeResize(n + centres, d.coded.cols());
  d.coded.bottomRows(centres).setZero();
  d.points.insert(d.points.end(), centres, PointType::centre);
}

void identity_order(Design& d) {
  d.run_order.resize(d.runs());
  for (int i = 0; i < d.runs(); ++i) d.run_order[i] = i;
}

// Yates standard order: column j of run i is +1 when bit j of i is set.
Eigen::MatrixXd two_level_cube(int k) {
  int n = 1 << k;
  Eigen::MatrixXd m(n, k);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) m(i, j) = ((i >> j) & 1) ? 1.0 : -1.0;
  return m;
}

// Published first rows (Plackett and Burman, 1946).
const char* pb_first_row(int runs) {
  if (runs == 12) return "++-+++---+-";
  if (runs == 20) return "++--++++-+-+----++-";
  return nullptr;
}

std::string format_number(double v, int digits) {
  return v == 0 ? "0" : format_g(v, digits);  // "0", not "-0"
}

}  // namespace

std::string point_type_name(PointType t) {
  switch (t) {
    case PointType::factorial: return "factorial";
    case PointType::axial: return "axial";
    case PointType::edge: return "edge";
    case PointType::centre: return "centre";
    case PointType::path: return "path";
  }
  return "?";
}

Design full_factorial(const std::vector<Factor>& factors, int centres) {
  check_factors(factors, 1, 12, "a full factorial");
  check_centres(centres);
  Design d;
  d.type = "factorial";
  d.factors = factors;
  d.coded = two_level_cube(static_cast<int>(factors.size()));
  d.points.assign(d.coded.rows(), PointType::factorial);
  add_centres(d, centres);
  identity_order(d);
  return d;
}

std::vector<std::string> default_generators(int k, int p) {
  static const std::map<std::pair<int, int>, std::vector<std::string>> table = {
      {{3, 1}, {"C=AB"}},
      {{4, 1}, {"D=ABC"}},
      {{5, 1}, {"E=ABCD"}},
      {{5, 2}, {"D=AB", "E=AC"}},
      {{6, 1}, {"F=ABCDE"}},
      {{6, 2}, {"E=ABC", "F=BCD"}},
      {{6, 3}, {"D=AB", "E=AC", "F=BC"}},
      {{7, 1}, {"G=ABCDEF"}},
      {{7, 2}, {"F=ABCD", "G=ABDE"}},
      {{7, 3}, {"E=ABC", "F=BCD", "G=ACD"}},
      {{7, 4}, {"D=AB", "E=AC", "F=BC", "G=ABC"}},
      {{8, 2}, {"G=ABCD", "H=ABEF"}},
      {{8, 3}, {"F=ABC", "G=ABD", "H=BCDE"}},
      {{8, 4}, {"E=BCD", "F=ACD", "G=ABC", "H=ABD"}},
  };
  auto it = table.find({k, p});
  if (it == table.end())
    throw DesignError("no standard generators for a 2^(" + std::to_string(k) + "-" +
                      std::to_string(p) + ") design: give them explicitly (e.g. D=ABC)");
  return it->second;
}

Design fractional_factorial(const std::vector<Factor>& factors,
                            const std::vector<std::string>& generators, int centres) {
  check_factors(factors, 3, 15, "a fractional factorial");
  check_centres(centres);
  int k = static_cast<int>(factors.size());
  int p = static_cast<int>(generators.size());
  if (p < 1 || p > k - 2)
    throw DesignError("a fractional factorial of " + std::to_string(k) + " factors needs 1 to " +
                      std::to_string(k - 2) + " generators, got " + std::to_string(p));
  int base = k - p;
  Eigen::MatrixXd cube = two_level_cube(base);
  Design d;
  d.type = "fractional";
  d.factors = factors;
  d.generators = generators;
  d.coded.resize(cube.rows(), k);
  d.coded.leftCols(base) = cube;
  std::vector<bool> generated(k, false);
  for (const auto& g : generators) {
    auto eq = g.find('=');
    if (eq != 1) throw DesignError("generator '" + g + "' is not of the form D=ABC");
    int target = factor_from_letter(g[0]);
    if (target < base || target >= k)
      throw DesignError("generator '" + g + "': " + g.substr(0, 1) +
                        " is not one of the generated factors " + factor_letter(base) + ".." +
                        factor_letter(k - 1));
    if (generated[target]) throw DesignError("generator '" + g + "': factor generated twice");
    generated[target] = true;
    std::string rhs = g.substr(2);
    double sign = 1;
    if (!rhs.empty() && (rhs[0] == '-' || rhs[0] == '+')) {
      sign = rhs[0] == '-' ? -1 : 1;
      rhs = rhs.substr(1);
    }
    if (rhs.empty()) throw DesignError("generator '" + g + "' has an empty product");
    Eigen::VectorXd col = Eigen::VectorXd::Constant(cube.rows(), sign);
    std::vector<bool> used(base, false);
    for (char c : rhs) {
      int f = factor_from_letter(c);
      if (f < 0 || f >= base)
        throw DesignError("generator '" + g + "': '" + std::string(1, c) +
                          "' is not a base factor (" + factor_letter(0) + ".." +
                          factor_letter(base - 1) + ")");
      if (used[f]) throw DesignError("generator '" + g + "' repeats " + std::string(1, c));
      used[f] = true;
      col = col.cwiseProduct(cube.col(f));
    }
    d.coded.col(target) = col;
  }
  d.points.assign(d.coded.rows(), PointType::factorial);
  add_centres(d, centres);
  identity_order(d);
  return d;
}

Design plackett_burman(int runs, const std::vector<Factor>& factors, int centres) {
  const char* first = pb_first_row(runs);
  if (!first) throw DesignError("Plackett-Burman designs have 12 or 20 runs here, not " +
                                std::to_string(runs));
  check_factors(factors, 1, runs - 1, "this Plackett-Burman design");
  check_centres(centres);
  int cols = runs - 1;
  int k = static_cast<int>(factors.size());
  Design d;
  d.type = "pb" + std::to_string(runs);
  d.factors = factors;
  for (int j = k; j < cols; ++j) d.dummies.push_back(factor_letter(j));
  d.coded.resize(runs, cols);
  // Row r is the first row shifted right r times; the last row is all minus.
  for (int r = 0; r < cols; ++r)
    for (int j = 0; j < cols; ++j)
      d.coded(r, j) = first[((j - r) % cols + cols) % cols] == '+' ? 1.0 : -1.0;
  d.coded.row(cols).setConstant(-1.0);
  d.points.assign(runs, PointType::factorial);
  add_centres(d, centres);
  identity_order(d);
  return d;
}

AlphaSpec parse_alpha(const std::string& s) {
  if (s == "rotatable") return {AlphaKind::rotatable, 0};
  if (s == "orthogonal") return {AlphaKind::orthogonal, 0};
  if (s == "face" || s == "face-centred" || s == "face-centered") return {AlphaKind::face, 1};
  double v = 0;
  if (!parse_number(s, v) || !(v > 0))
    throw DesignError("alpha '" + s + "' is not rotatable, orthogonal, face or a positive number");
  return {AlphaKind::value, v};
}

double ccd_alpha(const AlphaSpec& spec, int k, int factorial_points, int centres) {
  double f = factorial_points;
  switch (spec.kind) {
    case AlphaKind::rotatable: return std::pow(f, 0.25);
    case AlphaKind::orthogonal: {
      double n = f + 2.0 * k + centres;
      return std::sqrt((std::sqrt(f * n) - f) / 2.0);
    }
    case AlphaKind::face: return 1.0;
    case AlphaKind::value: return spec.value;
  }
  return 0;
}

int snap_to_alpha(Eigen::MatrixXd& coded, double alpha, double tolerance) {
  int changed = 0;
  for (Eigen::Index i = 0; i < coded.rows(); ++i)
    for (Eigen::Index j = 0; j < coded.cols(); ++j) {
      double v = coded(i, j);
      if (std::fabs(std::fabs(v) - alpha) <= tolerance && std::fabs(v) != alpha) {
        coded(i, j) = v < 0 ? -alpha : alpha;
        ++changed;
      }
    }
  return changed;
}

Design central_composite(const std::vector<Factor>& factors, const AlphaSpec& alpha_spec,
                         int centres) {
  check_factors(factors, 2, 10, "a central composite design");
  check_centres(centres);
  int k = static_cast<int>(factors.size());
  Eigen::MatrixXd cube = two_level_cube(k);
  double alpha = ccd_alpha(alpha_spec, k, static_cast<int>(cube.rows()), centres);
  if (!(alpha > 0)) throw DesignError("alpha must be positive");
  Design d;
  d.type = "ccd";
  d.factors = factors;
  d.alpha = alpha;
  d.coded = Eigen::MatrixXd::Zero(cube.rows() + 2 * k, k);
  d.coded.topRows(cube.rows()) = cube;
  d.points.assign(cube.rows(), PointType::factorial);
  for (int j = 0; j < k; ++j) {
    d.coded(cube.rows() + 2 * j, j) = -alpha;
    d.coded(cube.rows() + 2 * j + 1, j) = alpha;
    d.points.push_back(PointType::axial);
    d.points.push_back(PointType::axial);
  }
  add_centres(d, centres);
  identity_order(d);
  return d;
}

Design box_behnken(const std::vector<Factor>& factors, int centres) {
  check_factors(factors, 3, 7, "a Box-Behnken design");
  check_centres(centres);
  int k = static_cast<int>(factors.size());
  // Blocks of factors varied together (0-based). k = 6 and 7 follow Box and Behnken (1960).
  std::vector<std::vector<int>> blocks;
  if (k <= 5) {
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) blocks.push_back({i, j});
  } else if (k == 6) {
    blocks = {{0, 1, 3}, {1, 2, 4}, {2, 3, 5}, {0, 3, 4}, {1, 4, 5}, {0, 2, 5}};
  } else {
    blocks = {{3, 4, 5}, {0, 5, 6}, {1, 4, 6}, {0, 1, 3}, {2, 3, 6}, {0, 2, 4}, {1, 2, 5}};
  }
  Design d;
  d.type = "bbd";
  d.factors = factors;
  int per_block = 1 << blocks[0].size();
  d.coded = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(blocks.size()) * per_block, k);
  int row = 0;
  for (const auto& b : blocks) {
    Eigen::MatrixXd cube = two_level_cube(static_cast<int>(b.size()));
    for (int r = 0; r < cube.rows(); ++r, ++row)
      for (size_t j = 0; j < b.size(); ++j) d.coded(row, b[j]) = cube(r, j);
  }
  d.points.assign(d.coded.rows(), PointType::edge);
  add_centres(d, centres);
  identity_order(d);
  return d;
}

Design steepest_path(const std::vector<Factor>& factors, const Eigen::VectorXd& slopes,
                     double base_step, int steps, bool ascent, int base_factor) {
  check_factors(factors, 1, 25, "a steepest-ascent path");
  int k = static_cast<int>(factors.size());
  if (slopes.size() != k)
    throw DesignError("a steepest-ascent path needs one slope per factor (" + std::to_string(k) +
                      "), got " + std::to_string(slopes.size()));
  if (steps < 1) throw DesignError("a steepest-ascent path needs at least one step");
  if (!(base_step > 0)) throw DesignError("the base step must be positive");
  if (base_factor < 0) slopes.cwiseAbs().maxCoeff(&base_factor);
  if (base_factor >= k) throw DesignError("base factor out of range");
  double b = std::fabs(slopes[base_factor]);
  if (b == 0) throw DesignError("the base factor's slope is zero: no direction to follow");
  Eigen::VectorXd delta = slopes / b * base_step * (ascent ? 1.0 : -1.0);
  Design d;
  d.type = "path";
  d.factors = factors;
  d.coded.resize(steps + 1, k);
  for (int s = 0; s <= steps; ++s) d.coded.row(s) = (static_cast<double>(s) * delta).transpose();
  d.points.assign(steps + 1, PointType::path);
  identity_order(d);
  return d;
}

void randomise_run_order(Design& design, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  // Unbiased draw in [0, n): reject the top sliver of the 64-bit range. std::shuffle and
  // std::uniform_int_distribution are implementation-defined, so they are avoided.
  auto below = [&](std::uint64_t n) {
    std::uint64_t limit = ~std::uint64_t(0) - (~std::uint64_t(0) % n);
    std::uint64_t x;
    do x = rng();
    while (x >= limit);
    return x % n;
  };
  identity_order(design);
  for (int i = design.runs() - 1; i > 0; --i)
    std::swap(design.run_order[i], design.run_order[below(static_cast<std::uint64_t>(i) + 1)]);
}

Table design_table(const Design& design, int digits) {
  Table t;
  t.columns = {"Std", "Run", "Type"};
  for (const auto& f : design.factors) t.columns.push_back(f.name);
  for (const auto& f : design.factors) t.columns.push_back(f.name + "_coded");
  for (const auto& name : design.dummies) t.columns.push_back("dummy_" + name);
  int k = static_cast<int>(design.factors.size());
  for (int r = 0; r < design.runs(); ++r) {
    int s = design.run_order[r];
    std::vector<std::string> row = {std::to_string(s + 1), std::to_string(r + 1),
                                    point_type_name(design.points[s])};
    for (int j = 0; j < k; ++j) row.push_back(format_number(design.actual(s, j), digits));
    for (int j = 0; j < k; ++j) row.push_back(format_number(design.coded(s, j), digits));
    for (size_t j = 0; j < design.dummies.size(); ++j)
      row.push_back(format_number(design.coded(s, k + static_cast<int>(j)), digits));
    t.add_row(std::move(row), 0);
  }
  return t;
}

}  // namespace repose::stats
