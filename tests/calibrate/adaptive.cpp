// The simulator-in-the-loop mode: the surrogate's pieces checked against closed forms, then the
// loop on the drop test reaching the measured e within 1 % well inside its budget.
#include <catch2/catch.hpp>

#include <cmath>

#include "calibrate/adaptive_loop.h"
#include "calibrate/gaussian_process.h"
#include "calibrate_support.h"

using namespace repose;
using namespace repose::calibrate;

TEST_CASE("expected improvement towards a target matches numerical integration") {
  // E[max(0, b - |Y - t|)] for Y ~ N(m, s^2) by the trapezoid rule on a fine grid (error
  // ~1e-9 at 20001 points), against the closed form.
  for (double m : {0.3, 0.44, 0.5, 0.9})
    for (double s : {0.01, 0.05, 0.2})
      for (double b : {0.005, 0.05, 0.3}) {
        const double t = 0.44;
        double sum = 0;
        const int n = 20001;
        const double lo = t - b, hi = t + b, h = (hi - lo) / (n - 1);
        for (int i = 0; i < n; ++i) {
          double y = lo + i * h;
          double f = (b - std::abs(y - t)) * std::exp(-0.5 * std::pow((y - m) / s, 2)) / (s * std::sqrt(2 * M_PI));
          sum += (i == 0 || i == n - 1 ? 0.5 : 1.0) * f * h;
        }
        CHECK(expected_improvement_to_target(m, s, t, b) == Approx(sum).margin(1e-8));
      }
  CHECK(expected_improvement_to_target(0.45, 0.0, 0.44, 0.05) == Approx(0.04));  // no uncertainty
}

TEST_CASE("the Gaussian process interpolates its runs and is uncertain away from them") {
  Eigen::MatrixXd x(5, 1);
  Eigen::VectorXd y(5);
  for (int i = 0; i < 5; ++i) {
    x(i, 0) = -1 + 0.5 * i;
    y[i] = std::sin(2 * x(i, 0));
  }
  GaussianProcess gp = fit_gaussian_process(x, y);
  for (int i = 0; i < 5; ++i) {
    Eigen::VectorXd p = x.row(i).transpose();
    CHECK(gp.mean(p) == Approx(y[i]).margin(2e-3));  // the nugget allows a little smoothing
  }
  Eigen::VectorXd mid(1), far(1);
  mid[0] = -0.25;
  far[0] = 3.0;
  CHECK(gp.mean(mid) == Approx(std::sin(-0.5)).margin(0.02));  // smooth function, dense runs
  CHECK(gp.sd(far) > 10 * gp.sd(mid));
}

TEST_CASE("Halton start points fill the coded cube") {
  auto p = halton_points(2, 1, 3);
  CHECK(p[0][0] == Approx(0.0));      // base 2: 1/2 -> coded 0
  CHECK(p[1][0] == Approx(-0.5));     // 1/4
  CHECK(p[2][0] == Approx(0.5));      // 3/4
  CHECK(p[0][1] == Approx(-1.0 / 3));  // base 3: 1/3
}

TEST_CASE("the adaptive loop calibrates the drop test's e within 1 % in under 20 simulations") {
  std::string dir = test::scratch_dir("adaptive");
  test::write_text(dir + "/plan.toml",
                   "[campaign]\nexperiment = \"drop\"\ncase = \"" + test::drop_case_path() + "\"\nmode = \"adaptive\"\n"
                   "[response]\nname = \"restitution\"\nmeasured = 0.44\nmeasured_sd = 0.02\ntolerance = 0.01\n"
                   "[set]\n\"experiment.drop_height\" = 0.1\n\"simulation.rayleigh_fraction\" = 0.03\n"
                   "[[factor]]\nname = \"e\"\nkey = \"interaction.stalk/steel.restitution\"\nlow = 0.2\nhigh = 0.8\n"
                   "[adaptive]\ninitial = 3\nbudget = 19\n[verification]\nruns = 2\n");
  auto run = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2");
  INFO(run.output);
  REQUIRE(run.status == 0);
  auto s = nlohmann::json::parse(test::read_text_file(dir + "/out/summary.json"));
  int to_target = s["simulations_to_target"];
  CHECK(to_target >= 1);
  CHECK(to_target < 20);
  CHECK(int(s["loop_runs"]) == to_target);  // the loop stops at the first run that meets it
  CHECK(std::abs(double(s["verification"]["relative_error"])) <= 0.01);
  // Uncertainty of e: measured sd 0.02 through the slope de_out/de_in (~1): about 0.02.
  CHECK(double(s["parameters"]["e"]["uncertainty"]) == Approx(0.02).epsilon(0.15));
  CHECK(std::filesystem::exists(dir + "/out/convergence.png"));
  // Resuming re-proposes the same points from the stored runs and simulates nothing.
  auto again = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2");
  CHECK(again.status == 0);
  CHECK(again.output.find("(0 run now)") != std::string::npos);
}
