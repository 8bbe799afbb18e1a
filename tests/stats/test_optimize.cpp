// Optimisation of fitted models inside the coded region, and the set of near-optimal
// parameter combinations that goes with every optimum.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "stats/anova.h"
#include "stats/csv_table.h"
#include "stats/dataset.h"
#include "stats/design.h"
#include "stats/factor.h"
#include "stats/model_terms.h"
#include "stats/optimize.h"
#include "stats/polynomial.h"

using namespace repose::stats;

namespace {

Polynomial printed_equation(int k, const std::vector<std::pair<const char*, double>>& terms) {
  Polynomial p;
  for (const auto& [name, c] : terms) {
    p.terms.push_back(parse_term(name, k));
    p.coef.push_back(c);
  }
  return p;
}

}  // namespace

TEST_CASE("cabbage Eq. 9 minimised at A = 0.42: the paper's chosen point is not the minimum",
          "[stats][optimize][paper]") {
  // Eq. 9 as printed (coded units) and Table 9's coding: A e 0.40..0.44, B mu_s 0.20..0.40,
  // C mu_r 0.02..0.04. Constraints of Eq. 10: A = 0.42, -1.682 <= B, C <= 1.682.
  Polynomial eq9 = printed_equation(3, {{"Intercept", 1.37}, {"B", -1.81}, {"C", -0.68},
                                        {"BC", 1.07}, {"A^2", 0.57}, {"B^2", 1.89}, {"C^2", 0.72}});
  const std::vector<Factor> f = {{"e", 0.40, 0.44}, {"mu_s", 0.20, 0.40}, {"mu_r", 0.02, 0.04}};
  Box box = Box::cube(3, 1.682);
  box.fix(0, f[0].to_coded(0.42));
  OptimizeOptions opt;
  opt.tolerance = 0.05;  // percentage points of angle error
  Optimum best = optimize(eq9, box, {GoalKind::minimize, 0}, opt);

  // Stationary point of Eq. 9 at A = 0: 3.78 B + 1.07 C = 1.81, 1.07 B + 1.44 C = 0.68.
  const double b_star = (1.81 * 1.44 - 1.07 * 0.68) / (3.78 * 1.44 - 1.07 * 1.07);
  const double c_star = (3.78 * 0.68 - 1.07 * 1.81) / (3.78 * 1.44 - 1.07 * 1.07);
  CHECK(best.x[0] == Approx(0).margin(1e-12));  // 0.42 is the centre of 0.40..0.44
  CHECK(best.x[1] == Approx(b_star).margin(1e-6));
  CHECK(best.x[2] == Approx(c_star).margin(1e-6));
  const double mu_s = f[1].to_actual(best.x[1]), mu_r = f[2].to_actual(best.x[2]);
  CHECK(mu_s == Approx(0.3437).margin(0.0001));
  CHECK(mu_r == Approx(0.03147).margin(0.00001));
  CHECK(best.value == Approx(0.9243).margin(0.0001));

  // The paper's choice, mu_s = 0.457 and mu_r = 0.039 (coded B = 1.57, C = 0.90), where it
  // reports a 0.96 % error. Eq. 9 gives 4.67 % there; the minimum is 0.92 % at
  // mu_s = 0.344, mu_r = 0.0315. The reported 0.96 % is close to the minimum's value, so the
  // paper's parameter values, not its optimisation, look mistaken.
  Eigen::VectorXd paper(3);
  paper << 0.0, f[1].to_coded(0.457), f[2].to_coded(0.039);
  PointComparison cmp = compare_point(eq9, {GoalKind::minimize, 0}, best, box, paper);
  CHECK(cmp.inside_box);
  CHECK_FALSE(cmp.in_near_set);
  CHECK(cmp.value == Approx(4.670).margin(0.001));
  CHECK(cmp.gap == Approx(3.746).margin(0.001));
  char line[200];
  std::snprintf(line, sizeof line,
                "Eq. 9 minimum %.4f at mu_s %.4f mu_r %.5f; paper's 0.457/0.039 gives %.3f", best.value,
                mu_s, mu_r, cmp.value);
  WARN(line);

  // Near-optimal set: an ellipse around the minimum, within the box, all within 0.05.
  CHECK(best.set_size > 10);
  for (double v : best.representative_values) CHECK(v <= best.value + 0.05 + 1e-12);
  CHECK(best.set_lower[1] < best.x[1]);
  CHECK(best.set_upper[2] > best.x[2]);
  CHECK(best.set_lower[0] == best.x[0]);  // A stays fixed
  CHECK(best.set_upper[0] == best.x[0]);
}

TEST_CASE("target: one angle of repose is matched by a whole surface of parameter sets",
          "[stats][optimize][paper]") {
  // Cotton Eq. 3 (coded), target 24.79 deg inside the factorial cube, as in the paper's
  // optimisation. Every representative must hit the target; together they span the cube.
  Polynomial eq3 = printed_equation(3, {{"Intercept", 25.09}, {"A", 1.67}, {"B", 1.25},
                                        {"C", 2.85}, {"AB", -0.32}, {"AC", 1.42}, {"BC", 2.14},
                                        {"A^2", 1.84}, {"B^2", 2.41}, {"C^2", 1.09}});
  OptimizeOptions opt;
  opt.tolerance = 0.1;
  Optimum best = optimize(eq3, Box::cube(3, 1), {GoalKind::target, 24.79}, opt);
  CHECK(best.target_reached);
  CHECK(best.value == Approx(24.79).margin(1e-6));
  REQUIRE(best.representatives.size() >= 6);
  for (double v : best.representative_values) CHECK(v == Approx(24.79).margin(1e-4));
  // The set is two-dimensional and wide: each factor varies over much of its range.
  for (int i = 0; i < 3; ++i) CHECK(best.set_upper[i] - best.set_lower[i] > 0.8);
  CHECK(best.principal_direction.norm() == Approx(1.0));
  // The paper's (0.31, 0.62, 0.02), coded (-0.6, 0.7, -1), gives 24.53 with the printed
  // coefficients (24.55 with the refitted ones): 0.26 deg off the target, outside this 0.1 deg set.
  Eigen::VectorXd paper(3);
  paper << -0.6, 0.7, -1.0;
  PointComparison cmp = compare_point(eq3, {GoalKind::target, 24.79}, best, Box::cube(3, 1), paper);
  CHECK(cmp.value == Approx(24.5347).margin(0.0001));
  CHECK_FALSE(cmp.in_near_set);
}

TEST_CASE("maximise and minimise a concave quadratic inside the box", "[stats][optimize]") {
  // y = 10 - (x1 - 0.3)^2 - 2 (x2 + 0.5)^2 + x1 x2: interior maximum, minimum at a corner.
  Objective y = [](const Eigen::VectorXd& x) {
    return 10 - (x[0] - 0.3) * (x[0] - 0.3) - 2 * (x[1] + 0.5) * (x[1] + 0.5) + x[0] * x[1];
  };
  // Stationary point: -2(x1 - 0.3) + x2 = 0, -4(x2 + 0.5) + x1 = 0.
  const double x1 = (0.6 * 4 - 2) / (8 - 1), x2 = 2 * x1 - 0.6;
  Optimum mx = optimize(y, Box::cube(2, 1), {GoalKind::maximize, 0});
  CHECK(mx.x[0] == Approx(x1).margin(1e-6));
  CHECK(mx.x[1] == Approx(x2).margin(1e-6));
  Optimum mn = optimize(y, Box::cube(2, 1), {GoalKind::minimize, 0});
  Eigen::VectorXd corner(2);
  corner << -1, 1;
  CHECK((mn.x - corner).norm() < 1e-9);
  CHECK(mn.value == Approx(y(corner)));
  // Deterministic: the same call gives the same answer to the last bit.
  Optimum again = optimize(y, Box::cube(2, 1), {GoalKind::maximize, 0});
  CHECK(again.x == mx.x);
  CHECK(again.representatives.size() == mx.representatives.size());
}

TEST_CASE("Derringer desirability of several responses", "[stats][optimize]") {
  DesirabilityGoal up{GoalKind::maximize, -1, 1, 0, 1, 1};
  DesirabilityGoal down{GoalKind::minimize, -1, 1, 0, 1, 1};
  DesirabilityGoal aim{GoalKind::target, 0, 10, 4, 1, 1};
  CHECK(desirability(0, up) == Approx(0.5));
  CHECK(desirability(2, up) == 1);
  CHECK(desirability(-2, up) == 0);
  CHECK(desirability(0.5, down) == Approx(0.25));
  CHECK(desirability(2, aim) == Approx(0.5));
  CHECK(desirability(7, aim) == Approx(0.5));
  CHECK(desirability(4, aim) == 1);
  CHECK(desirability(11, aim) == 0);
  // Conflicting goals on the same response: D = sqrt((x + 1)/2 (1 - x)/2), best at x = 0.
  Objective same = [](const Eigen::VectorXd& x) { return x[0]; };
  Optimum o = optimize_desirability({same, same}, {up, down}, Box::cube(1, 1));
  CHECK(o.x[0] == Approx(0).margin(1e-6));
  CHECK(o.value == Approx(0.5).margin(1e-9));
  // Two factors: y1 = x1 maximised, y2 = x1 + x2 aimed at 4 on [0, 10] (coded [-1, 1]
  // leaves y2 in [-2, 2], below the range) -> D = 0 everywhere except y2 > 0.
  DesirabilityGoal aim2{GoalKind::target, 0, 1, 0.5, 1, 1};
  Objective y1 = [](const Eigen::VectorXd& x) { return x[0]; };
  Objective y2 = [](const Eigen::VectorXd& x) { return x[0] + x[1]; };
  Optimum o2 = optimize_desirability({y1, y2}, {up, aim2}, Box::cube(2, 1));
  CHECK(o2.value == Approx(1.0).margin(1e-6));  // x1 = 1, x2 = -0.5
  CHECK(o2.x[0] == Approx(1).margin(1e-6));
  CHECK(o2.x[1] == Approx(-0.5).margin(1e-6));
  CHECK_THROWS(desirability(0, DesirabilityGoal{GoalKind::maximize, 1, 1, 0, 1, 1}));
}
