// Designs checked against their defining properties: run counts, balance, orthogonality,
// aliasing of fractions, rotatability and orthogonal blocking of the CCD alpha, and
// agreement with the designs the seeds ran (which Design-Expert generated).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "stats/anova.h"
#include "stats/csv_table.h"
#include "stats/dataset.h"
#include "stats/design.h"
#include "stats/errors.h"
#include "stats/model_terms.h"
#include "stats/regression.h"

using namespace repose::stats;

namespace {

std::vector<Factor> factors(int k) {
  std::vector<Factor> f;
  for (int i = 0; i < k; ++i) f.push_back({"x" + std::to_string(i + 1), 0.1 * i, 0.1 * i + 1});
  return f;
}

// Columns balanced (sum 0 over the non-centre runs) and mutually orthogonal.
void check_orthogonal(const Eigen::MatrixXd& m) {
  Eigen::MatrixXd g = m.transpose() * m;
  for (Eigen::Index i = 0; i < g.rows(); ++i) {
    CHECK(m.col(i).sum() == Approx(0).margin(1e-12));
    for (Eigen::Index j = 0; j < g.cols(); ++j)
      if (i != j) CHECK(g(i, j) == Approx(0).margin(1e-12));
  }
}

std::multiset<std::vector<long long>> row_set(const Eigen::MatrixXd& m) {
  std::multiset<std::vector<long long>> s;
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    std::vector<long long> r;
    for (Eigen::Index j = 0; j < m.cols(); ++j) r.push_back(std::llround(m(i, j) * 1e4));
    s.insert(r);
  }
  return s;
}

std::string data_path(const std::string& name) {
  return std::string(REPOSE_SOURCE_DIR) + "/tests/stats/data/" + name;
}

}  // namespace

TEST_CASE("Plackett-Burman 12 and 20: run counts, balance, orthogonality", "[stats][design]") {
  Design pb12 = plackett_burman(12, factors(6), 3);
  CHECK(pb12.runs() == 15);
  CHECK(pb12.coded.cols() == 11);
  CHECK(pb12.dummies == std::vector<std::string>{"G", "H", "J", "K", "L"});
  check_orthogonal(pb12.coded.topRows(12));
  CHECK(pb12.coded.bottomRows(3).isZero());
  Design pb20 = plackett_burman(20, factors(19), 0);
  CHECK(pb20.runs() == 20);
  CHECK(pb20.dummies.empty());
  check_orthogonal(pb20.coded);
  CHECK_THROWS_AS(plackett_burman(16, factors(3), 0), DesignError);
  CHECK_THROWS_AS(plackett_burman(12, factors(12), 0), DesignError);
}

TEST_CASE("Plackett-Burman 12 is the design the cotton-stalk study ran (Table 3)", "[stats][design]") {
  // Design-Expert's 12-run design uses the same first row; Table 3 lists its rows in random
  // order with the dummy columns omitted and three centre points added.
  Table t = read_csv(data_path("cotton_table3_pb.csv"));
  DataSet d = dataset_from_table(t, {"A", "B", "C", "D", "E", "F"}, "Y");
  Design pb12 = plackett_burman(12, factors(6), 3);
  CHECK(row_set(d.coded) == row_set(pb12.coded.leftCols(6)));
}

TEST_CASE("full and fractional factorials: orthogonality and aliasing", "[stats][design]") {
  Design full = full_factorial(factors(3), 2);
  CHECK(full.runs() == 10);
  Eigen::MatrixXd X = model_matrix(build_model(ModelKind::interaction, 3), full.coded.topRows(8));
  check_orthogonal(X.rightCols(X.cols() - 1));

  // 2^(5-2) with D = AB, E = AC: resolution III, 8 runs, D is the AB column.
  Design frac = fractional_factorial(factors(5), {"D=AB", "E=AC"}, 0);
  CHECK(frac.runs() == 8);
  check_orthogonal(frac.coded);
  CHECK(frac.coded.col(3) == frac.coded.col(0).cwiseProduct(frac.coded.col(1)));
  CHECK(frac.coded.col(4) == frac.coded.col(0).cwiseProduct(frac.coded.col(2)));
  // A model with both D and AB cannot be fitted: the error names the aliased term.
  std::vector<Term> terms = build_model(ModelKind::linear, 5);
  terms.push_back(parse_term("AB", 5));
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(8, 1, 8);
  CHECK_THROWS_AS(analyse(frac.coded, y, terms), ModelError);
  CHECK_THROWS_WITH(analyse(frac.coded, y, terms), Catch::Contains("aliased"));

  // 2^(4-1), D = ABC (resolution IV): main effects orthogonal to all two-factor interactions.
  Design half = fractional_factorial(factors(4), default_generators(4, 1), 0);
  CHECK(half.runs() == 8);
  Eigen::MatrixXd X4 = model_matrix(build_model(ModelKind::interaction, 4), half.coded);
  for (int main = 1; main <= 4; ++main)
    for (int fi = 5; fi < X4.cols(); ++fi) CHECK(X4.col(main).dot(X4.col(fi)) == 0);
  CHECK(fractional_factorial(factors(4), {"D=-ABC"}, 0).coded.col(3) == -half.coded.col(3));

  CHECK_THROWS_AS(fractional_factorial(factors(5), {"D=AB", "D=AC"}, 0), DesignError);
  CHECK_THROWS_AS(fractional_factorial(factors(5), {"D=AB", "E=AD"}, 0), DesignError);
  CHECK_THROWS_AS(fractional_factorial(factors(5), {"D=AB", "E=AX"}, 0), DesignError);
  CHECK_THROWS_AS(default_generators(20, 3), DesignError);
}

TEST_CASE("central composite: run count, rotatable and orthogonal alpha", "[stats][design]") {
  Design ccd = central_composite(factors(3), {AlphaKind::rotatable, 0}, 6);
  CHECK(ccd.runs() == 20);
  CHECK(ccd.alpha == Approx(std::pow(8.0, 0.25)));
  CHECK(ccd.alpha == Approx(1.68179).margin(1e-5));
  // Rotatable: the prediction variance f(x)' (X'X)^-1 f(x) depends only on the distance from
  // the centre. Compare points at radius 1.2 in several directions.
  auto model = build_model(ModelKind::quadratic, 3);
  LeastSquaresFit fit = least_squares(model_matrix(model, ccd.coded), Eigen::VectorXd::Ones(20));
  auto variance = [&](Eigen::Vector3d dir) {
    Eigen::MatrixXd x = (1.2 * dir.normalized()).transpose();
    Eigen::VectorXd f = model_matrix(model, x).row(0).transpose();
    return f.dot(fit.xtx_inverse * f);
  };
  double v0 = variance({1, 0, 0});
  CHECK(variance({0, 1, 0}) == Approx(v0).epsilon(1e-10));
  CHECK(variance({1, 1, 0}) == Approx(v0).epsilon(1e-10));
  CHECK(variance({1, -2, 3}) == Approx(v0).epsilon(1e-10));
  // A non-rotatable alpha breaks it.
  Design face = central_composite(factors(3), {AlphaKind::face, 0}, 6);
  CHECK(face.alpha == 1);
  LeastSquaresFit ff = least_squares(model_matrix(model, face.coded), Eigen::VectorXd::Ones(20));
  auto fvar = [&](Eigen::Vector3d dir) {
    Eigen::MatrixXd x = (1.2 * dir.normalized()).transpose();
    Eigen::VectorXd f = model_matrix(model, x).row(0).transpose();
    return f.dot(ff.xtx_inverse * f);
  };
  CHECK(std::fabs(fvar({1, 0, 0}) - fvar({1, 1, 1})) > 1e-3);

  // Orthogonal alpha: the centred quadratic columns are uncorrelated.
  for (int centres : {2, 6, 9}) {
    Design orth = central_composite(factors(3), {AlphaKind::orthogonal, 0}, centres);
    Eigen::MatrixXd sq = orth.coded.array().square().matrix();
    sq = sq.rowwise() - sq.colwise().mean();
    Eigen::MatrixXd g = sq.transpose() * sq;
    CHECK(g(0, 1) == Approx(0).margin(1e-10));
    CHECK(g(1, 2) == Approx(0).margin(1e-10));
  }
  CHECK(ccd_alpha({AlphaKind::orthogonal, 0}, 3, 8, 6) == Approx(1.5247).margin(1e-4));
  CHECK(central_composite(factors(2), parse_alpha("1.5"), 5).alpha == 1.5);
  CHECK(central_composite(factors(4), parse_alpha("rotatable"), 6).runs() == 30);
  CHECK_THROWS_AS(parse_alpha("-1"), DesignError);
  CHECK_THROWS_AS(parse_alpha("steep"), DesignError);
}

TEST_CASE("central composite k = 3 is the design both seeds ran (Tables 7 and 10)",
          "[stats][design]") {
  Design ccd = central_composite(factors(3), {AlphaKind::rotatable, 0}, 6);
  for (auto [file, cols] : {std::pair<const char*, std::vector<std::string>>{"cotton_table7_ccd.csv", {"a", "b", "c"}},
                            {"cabbage_table10_ccd.csv", {"A", "B", "C"}}}) {
    DataSet d = dataset_from_table(read_csv(data_path(file)), cols, "Y");
    CHECK(snap_to_alpha(d.coded, ccd.alpha) == 6);
    CHECK(row_set(d.coded) == row_set(ccd.coded));
  }
}

TEST_CASE("Box-Behnken: run counts and balance", "[stats][design]") {
  Design b3 = box_behnken(factors(3), 3);
  CHECK(b3.runs() == 15);  // 12 edge midpoints + 3 centres
  const int expected[] = {0, 0, 0, 12, 24, 40, 48, 56};
  for (int k = 3; k <= 7; ++k) {
    Design b = box_behnken(factors(k), 0);
    CHECK(b.runs() == expected[k]);
    check_orthogonal(b.coded);
    // Every factor is varied equally often, at +-1 only.
    Eigen::VectorXd nonzero = b.coded.cwiseAbs().colwise().sum();
    CHECK(nonzero.minCoeff() == nonzero.maxCoeff());
    CHECK(b.coded.cwiseAbs().maxCoeff() == 1);
  }
  // The quadratic model is estimable (k = 3 with centre points).
  CHECK_NOTHROW(analyse(b3.coded, Eigen::VectorXd::LinSpaced(15, 0, 1).array().square().matrix(),
                        build_model(ModelKind::quadratic, 3)));
  CHECK_THROWS_AS(box_behnken(factors(2), 1), DesignError);
}

TEST_CASE("steepest ascent path follows the first-order coefficients", "[stats][design]") {
  Eigen::VectorXd b(3);
  b << 1.2, -0.4, 2.4;  // C has the largest effect: it moves one unit per step
  Design up = steepest_path(factors(3), b, 1.0, 5, true);
  CHECK(up.runs() == 6);
  CHECK(up.coded.row(0).isZero());
  for (int s = 1; s <= 5; ++s) {
    CHECK(up.coded(s, 2) == Approx(s));
    CHECK(up.coded(s, 0) == Approx(0.5 * s));
    CHECK(up.coded(s, 1) == Approx(-s / 6.0));
  }
  Design down = steepest_path(factors(3), b, 0.5, 2, false);
  CHECK(down.coded(2, 2) == Approx(-1.0));
  CHECK(down.actual(2, 2) == Approx(factors(3)[2].to_actual(-1.0)));
  CHECK_THROWS_AS(steepest_path(factors(3), Eigen::VectorXd::Zero(3), 1, 3, true), DesignError);
}

TEST_CASE("randomised run order: a seeded, reproducible permutation", "[stats][design]") {
  Design a = central_composite(factors(3), {AlphaKind::rotatable, 0}, 6);
  Design b = a, c = a;
  randomise_run_order(a, 42);
  randomise_run_order(b, 42);
  randomise_run_order(c, 43);
  CHECK(a.run_order == b.run_order);
  CHECK(a.run_order != c.run_order);
  std::vector<int> sorted = a.run_order;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < a.runs(); ++i) CHECK(sorted[i] == i);
  // Pinned: std::mt19937_64 is fully specified by the standard and the bounded draw is ours,
  // so the order must not change between platforms, compilers or releases.
  CHECK(a.run_order == std::vector<int>{7, 1, 11, 13, 2, 19, 16, 14, 0, 15, 9, 12, 10, 17, 8,
                                        18, 3, 4, 5, 6});
  Table t = design_table(a);
  CHECK(t.rows() == 20);
  CHECK(t.columns[0] == "Std");
  CHECK(t.cells[0][0] == std::to_string(a.run_order[0] + 1));
  CHECK(t.has_column("x1_coded"));
}

TEST_CASE("design requests that cannot be built give clear errors", "[stats][design]") {
  CHECK_THROWS_AS(parse_factor("mu_s:0.5:0.2"), DesignError);
  CHECK_THROWS_WITH(parse_factor("mu_s:0.5:0.2"), Catch::Contains("range reversed"));
  CHECK_THROWS_WITH(parse_factor("mu_s:0.5"), Catch::Contains("LOW:HIGH"));
  CHECK_THROWS_WITH(parse_factor("mu_s:a:0.2"), Catch::Contains("not LOW:HIGH"));
  CHECK_THROWS_WITH(parse_factors("a:0:1,a:1:2"), Catch::Contains("twice"));
  CHECK_THROWS_AS(full_factorial(factors(3), -1), DesignError);
  Factor f = parse_factor("e:0.40:0.44");
  CHECK(f.to_coded(0.44) == Approx(1));
  CHECK(f.to_actual(-1.682) == Approx(0.38636));
}
