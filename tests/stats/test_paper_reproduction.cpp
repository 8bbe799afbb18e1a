// The seeds' design tables, refitted by least squares, must give back the ANOVA tables and
// regression equations the papers printed from Design-Expert (issue 4; README, Calibration statistics).
//
// How a printed number is compared. The rule is "within 0.5 %" for coefficients, sums of
// squares and F, and "within 0.002" for p. A printed value with fewer than three significant
// digits cannot meet 0.5 % even when it is exact: "0.32" only says 0.315 <= x < 0.325. Such a
// value is accepted when the computed number rounds to the printed digits (within half a unit
// of the last printed digit). Every use of that allowance is listed in the test output, so
// nothing is loosened silently. A printed "<0.0001" is a bound and is checked as a bound.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "stats/anova.h"
#include "stats/csv_table.h"
#include "stats/dataset.h"
#include "stats/design.h"
#include "stats/model_terms.h"
#include "stats/polynomial.h"

using namespace repose::stats;

namespace {

std::string data_path(const std::string& name) {
  return std::string(REPOSE_SOURCE_DIR) + "/tests/stats/data/" + name;
}

int printed_decimals(const std::string& text) {
  auto dot = text.find('.');
  return dot == std::string::npos ? 0 : static_cast<int>(text.size() - dot - 1);
}

// True when `computed` agrees with the printed text under the rule above; `how` says which
// part of the rule was needed.
bool agrees(double computed, const std::string& printed, double rel_tol, std::string& how) {
  double v = 0;
  REQUIRE(parse_number(printed, v));
  double rel = std::fabs(computed - v) / std::max(std::fabs(v), 1e-300);
  if (rel <= rel_tol) {
    how = "within " + std::to_string(rel * 100).substr(0, 5) + " %";
    return true;
  }
  double half_unit = 0.5 * std::pow(10.0, -printed_decimals(printed));
  if (std::fabs(computed - v) <= half_unit * (1 + 1e-9)) {
    how = "rounds to the printed digits (" + std::to_string(rel * 100).substr(0, 5) +
          " % off, printed to " + std::to_string(printed_decimals(printed)) + " decimals)";
    return true;
  }
  how = "differs by " + std::to_string(rel * 100) + " %";
  return false;
}

void check_value(const std::string& what, double computed, const std::string& printed,
                 double rel_tol = 0.005) {
  std::string how;
  bool ok = agrees(computed, printed, rel_tol, how);
  char line[256];
  std::snprintf(line, sizeof line, "%-22s printed %-9s computed %-12.6g %s", what.c_str(),
                printed.c_str(), computed, how.c_str());
  if (!ok || how.rfind("within", 0) != 0) WARN(line);
  INFO(line);
  CHECK(ok);
}

void check_p(const std::string& what, double computed, const std::string& printed) {
  char line[256];
  std::snprintf(line, sizeof line, "%-22s p printed %-9s computed %.5f", what.c_str(),
                printed.c_str(), computed);
  INFO(line);
  if (!printed.empty() && printed[0] == '<') {
    double bound = 0;
    REQUIRE(parse_number(printed.substr(1), bound));
    CHECK(computed < bound);
    return;
  }
  double v = 0;
  REQUIRE(parse_number(printed, v));
  CHECK(std::fabs(computed - v) <= 0.002);
}

// Compares every printed cell of an ANOVA table (columns Source and any of SS, df, MS, F, p).
// `known` lists "Source/Column" cells that are documented findings, checked by the caller.
void check_anova(const ResponseSurface& rs, const Table& expected,
                 const std::vector<std::string>& known = {}) {
  for (int r = 0; r < expected.rows(); ++r) {
    const std::string source = expected.cells[r][expected.column_index("Source")];
    const AnovaRow& row = rs.row(source);
    auto cell = [&](const char* col) -> std::string {
      for (const auto& k : known)
        if (k == source + "/" + col) return "";
      return expected.has_column(col) ? expected.cells[r][expected.column_index(col)] : "";
    };
    if (!cell("SS").empty()) check_value(source + " SS", row.ss, cell("SS"));
    if (!cell("df").empty()) CHECK(row.df == std::stoi(cell("df")));
    if (!cell("MS").empty()) check_value(source + " MS", row.ms, cell("MS"));
    if (!cell("F").empty()) check_value(source + " F", row.f, cell("F"));
    if (!cell("p").empty()) check_p(source, row.p, cell("p"));
  }
}

// Coefficients printed in an equation, keyed by Design-Expert term names. `known` lists terms
// whose printed coefficient is a documented finding, checked by the caller.
void check_equation(const ResponseSurface& rs,
                    const std::vector<std::pair<std::string, std::string>>& printed,
                    const std::vector<std::string>& known = {}) {
  REQUIRE(rs.terms.size() == printed.size());
  for (const auto& [name, text] : printed) {
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    Term t = parse_term(name, rs.factors);
    double c = rs.polynomial().coefficient(t);
    check_value("coefficient " + name, c, text);
  }
}

ResponseSurface fit_ccd(const std::string& file, const std::vector<std::string>& cols,
                        bool exact_alpha, int* snapped = nullptr) {
  Table t = read_csv(data_path(file));
  DataSet d = dataset_from_table(t, cols, "Y");
  if (exact_alpha) {
    // The tables print 1.682; Design-Expert ran the rotatable alpha (2^3)^(1/4).
    int n = snap_to_alpha(d.coded, ccd_alpha({AlphaKind::rotatable, 0}, 3, 8, 6));
    if (snapped) *snapped = n;
  }
  return analyse(d.coded, d.y, build_model(ModelKind::quadratic, 3));
}

}  // namespace

TEST_CASE("cotton Table 4: Plackett-Burman ANOVA from Table 3", "[stats][paper]") {
  // Design-Expert fits the six real factors' main effects; the dummy columns and the three
  // centre points go to the residual (15 runs - 7 terms = 8 df, no separate curvature row:
  // F(1, 8) reproduces every printed p, F(1, 7) would not).
  Table t = read_csv(data_path("cotton_table3_pb.csv"));
  DataSet d = dataset_from_table(t, {"A", "B", "C", "D", "E", "F"}, "Y");
  ResponseSurface rs = analyse(d.coded, d.y, build_model(ModelKind::linear, 6));
  CHECK(rs.residual.df == 8);
  check_anova(rs, read_csv(data_path("cotton_table4_anova.csv")));
  // The paper ranks the significant factors C > E > B by p value.
  CHECK(rs.row("C").p < rs.row("E").p);
  CHECK(rs.row("E").p < rs.row("B").p);
  CHECK(rs.row("B").p < 0.05);
  CHECK(rs.row("A").p > 0.05);
}

TEST_CASE("cotton Eq. 3 and Table 8: CCD quadratic model from Table 7", "[stats][paper]") {
  int snapped = 0;
  ResponseSurface rs = fit_ccd("cotton_table7_ccd.csv", {"a", "b", "c"}, true, &snapped);
  CHECK(snapped == 6);
  check_equation(rs, {{"Intercept", "25.09"}, {"A", "1.67"}, {"B", "1.25"}, {"C", "2.85"},
                      {"AB", "-0.32"}, {"AC", "1.42"}, {"BC", "2.14"}, {"A^2", "1.84"},
                      {"B^2", "2.41"}, {"C^2", "1.09"}},
                 {"B^2"});
  // Finding: Eq. 3 (and Eq. 4, copied from it) print B^2 = 2.41, but the refit gives 2.424
  // (0.59 % off; it rounds to 2.42). Table 8 sides with the refit: a partial SS of 84.70 for
  // B^2 means |b| = sqrt(84.70 / c) with c = se^2 / MSE from the design, i.e. 2.424, whereas
  // 2.41 would give SS = 83.7. The paper's tables agree with each other; its equation has a
  // slip in this one coefficient.
  const Coefficient& b2 = rs.coefficients[8];
  REQUIRE(b2.term == "B^2");
  CHECK(b2.estimate == Approx(2.4243).margin(0.0005));
  double c_jj = b2.std_error * b2.std_error / rs.residual.ms;
  CHECK(2.4243 * 2.4243 / c_jj == Approx(84.70).epsilon(0.001));
  CHECK(2.41 * 2.41 / c_jj == Approx(83.70).epsilon(0.001));
  check_value("B^2 SS (Table 8)", rs.row("B^2").ss, "84.70");
  check_anova(rs, read_csv(data_path("cotton_table8_anova.csv")));
  // Printed below Table 8; with the exact alpha every printed digit comes back.
  check_value("R^2", rs.stats.r2, "0.9170", 0.0005);
  check_value("adjusted R^2", rs.stats.adj_r2, "0.8424", 0.0005);
  check_value("CV %", rs.stats.cv_percent, "6.22", 0.0005);
  check_value("Adeq Precision", rs.stats.adeq_precision, "12.715", 0.0001);
  CHECK(std::round(rs.stats.adeq_precision * 1000) / 1000 == Approx(12.715));
  CHECK(std::round(rs.stats.adj_r2 * 10000) / 10000 == Approx(0.8424));
}

TEST_CASE("cotton Table 8 from the printed axial level 1.682: the last digits move",
          "[stats][paper]") {
  // Finding: refitting the table exactly as printed (axial 1.682 instead of 1.68179) still
  // meets the 0.5 % rule but misses the last printed digit of three statistics. Design-Expert
  // used the rotatable alpha; the table rounds it. Both values are pinned here.
  ResponseSurface printed = fit_ccd("cotton_table7_ccd.csv", {"a", "b", "c"}, false);
  ResponseSurface exact = fit_ccd("cotton_table7_ccd.csv", {"a", "b", "c"}, true);
  CHECK(printed.model.ss == Approx(353.33).margin(0.005));     // paper 353.36, exact alpha 353.36
  CHECK(exact.model.ss == Approx(353.36).margin(0.005));
  CHECK(printed.stats.adeq_precision == Approx(12.710).margin(0.0005));  // paper 12.715
  CHECK(exact.stats.adeq_precision == Approx(12.715).margin(0.0005));
  CHECK(printed.stats.adj_r2 == Approx(0.8423).margin(0.00005));  // paper 0.8424
  CHECK(exact.stats.adj_r2 == Approx(0.8424).margin(0.00005));
  check_anova(printed, read_csv(data_path("cotton_table8_anova.csv")));
}

TEST_CASE("cotton Eq. 4: dropping the non-significant AB term", "[stats][paper]") {
  // The paper removes ab (p = 0.62) and keeps the other coefficients of Eq. 3 unchanged. AB is
  // orthogonal to every other column of the CCD, so a refit without it gives the same numbers.
  Table t = read_csv(data_path("cotton_table7_ccd.csv"));
  DataSet d = dataset_from_table(t, {"a", "b", "c"}, "Y");
  snap_to_alpha(d.coded, ccd_alpha({AlphaKind::rotatable, 0}, 3, 8, 6));
  Reduction red = reduce_backward(d.coded, d.y, build_model(ModelKind::quadratic, 3), 0.05);
  REQUIRE(red.removed.size() == 1);
  CHECK(red.removed[0].term == "AB");
  CHECK(red.removed[0].p == Approx(0.6223).margin(0.002));
  check_equation(red.model, {{"Intercept", "25.09"}, {"A", "1.67"}, {"B", "1.25"}, {"C", "2.85"},
                             {"AC", "1.42"}, {"BC", "2.14"}, {"A^2", "1.84"}, {"B^2", "2.41"},
                             {"C^2", "1.09"}},
                 {"B^2"});  // printed 2.41 as in Eq. 3; the refit gives 2.424 (see the Eq. 3 test)
  CHECK(red.model.polynomial().coefficient(parse_term("B^2", 3)) == Approx(2.4243).margin(0.0005));
}

TEST_CASE("cabbage Eq. 8 and Table 11: CCD quadratic model from Table 10", "[stats][paper]") {
  ResponseSurface rs = fit_ccd("cabbage_table10_ccd.csv", {"A", "B", "C"}, true);
  check_equation(rs, {{"Intercept", "1.37"}, {"A", "0.048"}, {"B", "-1.81"}, {"C", "-0.68"},
                      {"AB", "0.083"}, {"AC", "0.32"}, {"BC", "1.07"}, {"A^2", "0.57"},
                      {"B^2", "1.89"}, {"C^2", "0.72"}});
  check_anova(rs, read_csv(data_path("cabbage_table11_anova.csv")));
  // Not printed in the paper; pinned so that a regression in the statistics shows up.
  CHECK(rs.stats.r2 == Approx(0.9653).margin(0.0001));
  CHECK(rs.stats.adj_r2 == Approx(0.9340).margin(0.0001));
}

TEST_CASE("cabbage Table 11 from the printed axial level 1.682", "[stats][paper]") {
  // Finding: as for the cotton table, the printed 1.682 costs a last digit: the lack-of-fit mean
  // square becomes 0.5852 (printed 0.58; the exact alpha gives 0.5845). Its SS (2.926 vs
  // 2.92) and F still meet the rule.
  ResponseSurface rs = fit_ccd("cabbage_table10_ccd.csv", {"A", "B", "C"}, false);
  ResponseSurface exact = fit_ccd("cabbage_table10_ccd.csv", {"A", "B", "C"}, true);
  check_anova(rs, read_csv(data_path("cabbage_table11_anova.csv")), {"Lack of Fit/MS"});
  CHECK(rs.lack_of_fit->ms == Approx(0.5852).margin(0.0001));
  CHECK(exact.lack_of_fit->ms == Approx(0.5845).margin(0.0001));
}

TEST_CASE("cabbage Eq. 9: the paper's reduced model is not hierarchical", "[stats][paper]") {
  // Finding: Eq. 9 keeps A^2 but drops A, AB and AC. Backward elimination that keeps the model
  // hierarchical (Design-Expert's default) must keep A while A^2 stays; it drops AB and AC
  // only. Without the hierarchy rule the elimination gives exactly the terms of Eq. 9, with
  // Eq. 8's coefficients (A, AB, AC are orthogonal to the remaining columns).
  Table t = read_csv(data_path("cabbage_table10_ccd.csv"));
  DataSet d = dataset_from_table(t, {"A", "B", "C"}, "Y");
  snap_to_alpha(d.coded, ccd_alpha({AlphaKind::rotatable, 0}, 3, 8, 6));
  auto full = build_model(ModelKind::quadratic, 3);

  Reduction hier = reduce_backward(d.coded, d.y, full, 0.05, true);
  REQUIRE(hier.removed.size() == 2);
  CHECK(hier.removed[0].term == "AB");
  CHECK(hier.removed[1].term == "AC");
  CHECK(is_hierarchical(hier.model.terms));
  CHECK(hier.model.polynomial().coefficient(parse_term("A", 3)) == Approx(0.0485).margin(0.0005));

  Reduction free = reduce_backward(d.coded, d.y, full, 0.05, false);
  REQUIRE(free.removed.size() == 3);
  CHECK(free.removed[0].term == "A");
  CHECK(free.removed[1].term == "AB");
  CHECK(free.removed[2].term == "AC");
  CHECK_FALSE(is_hierarchical(free.model.terms));
  check_equation(free.model, {{"Intercept", "1.37"}, {"B", "-1.81"}, {"C", "-0.68"},
                              {"BC", "1.07"}, {"A^2", "0.57"}, {"B^2", "1.89"}, {"C^2", "0.72"}});
}

TEST_CASE("Type III (partial) sums of squares reproduce the papers, sequential do not",
          "[stats][paper]") {
  // The quadratic columns of a CCD are correlated, so the SS type matters there: Table 8's
  // A^2 = 49.03 and B^2 = 84.70 are partial; the sequential values are 34.2 and 78.1. The sum
  // of the printed term SS (374.8) exceeds the model SS (353.36), which sequential SS never do.
  Table t = read_csv(data_path("cotton_table7_ccd.csv"));
  DataSet d = dataset_from_table(t, {"a", "b", "c"}, "Y");
  snap_to_alpha(d.coded, ccd_alpha({AlphaKind::rotatable, 0}, 3, 8, 6));
  auto model = build_model(ModelKind::quadratic, 3);
  ResponseSurface partial = analyse(d.coded, d.y, model, SumOfSquaresType::partial);
  ResponseSurface sequential = analyse(d.coded, d.y, model, SumOfSquaresType::sequential);
  CHECK(partial.row("A^2").ss == Approx(49.03).epsilon(0.005));
  CHECK(sequential.row("A^2").ss == Approx(34.2).epsilon(0.01));
  CHECK(sequential.row("B^2").ss == Approx(78.1).epsilon(0.01));
  double seq_sum = 0;
  for (const auto& r : sequential.term_rows) seq_sum += r.ss;
  CHECK(seq_sum == Approx(sequential.model.ss).epsilon(1e-10));
  // Orthogonal terms agree under both types.
  CHECK(sequential.row("BC").ss == Approx(partial.row("BC").ss).epsilon(1e-10));
}

TEST_CASE("actual-unit equation of cotton Eq. 3 evaluates like the coded one", "[stats][paper]") {
  ResponseSurface rs = fit_ccd("cotton_table7_ccd.csv", {"a", "b", "c"}, true);
  std::vector<Factor> ranges = {{"mu_s_kl", 0.27, 0.47}, {"mu_s_kk", 0.45, 0.65},
                                {"mu_k_kk", 0.02, 0.06}};
  Polynomial actual = to_actual_units(rs.polynomial(), ranges);
  CHECK(actual.terms.size() == 10);
  // The optimum the paper reports (0.31, 0.62, 0.02), where the model predicts 24.41 deg.
  Eigen::VectorXd xa(3), xc(3);
  xa << 0.31, 0.62, 0.02;
  for (int i = 0; i < 3; ++i) xc[i] = ranges[i].to_coded(xa[i]);
  CHECK(actual(xa) == Approx(rs.predict(xc)).epsilon(1e-10));
  // Finding: the fitted Eq. 3 gives 24.55 at the printed point, not the printed 24.41. The
  // point is printed to two decimals; over the box it rounds from (a 0.305..0.315,
  // b 0.615..0.625, c 0.02..0.025, c cannot go below its bound) the model spans a range that
  // contains 24.41, so the printed prediction belongs to the unrounded optimum.
  CHECK(rs.predict(xc) == Approx(24.548).margin(0.001));
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int l = 0; l <= 10; ++l) {
        Eigen::VectorXd p(3);
        p << 0.305 + 0.001 * i, 0.615 + 0.001 * j, 0.02 + 0.0005 * l;
        double v = actual(p);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  CHECK(lo < 24.41);
  CHECK(hi > 24.41);
}
