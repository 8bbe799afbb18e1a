// The simulator-in-the-loop mode: the surrogate's pieces checked against closed forms, then the
// loop on the drop test reaching the measured e within 1 % well inside its budget.
#include <catch2/catch.hpp>

#include <cmath>

#include "calibrate/adaptive_loop.h"
#include "calibrate/gaussian_process.h"
#include "calibrate/noise.h"
#include "calibrate_support.h"
#include "util/math.h"

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
          double f = (b - std::abs(y - t)) * std::exp(-0.5 * std::pow((y - m) / s, 2)) / (s * std::sqrt(2 * repose::kPi));
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
                   "[response]\nname = \"restitution\"\nmeasured = 0.44\nmeasured_sd = 0.02\nmeasured_n = 25\ntolerance = 0.01\n"
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
  CHECK(int(s["loop_runs"]) == to_target);  // the loop stops as soon as the target is met
  CHECK(std::abs(double(s["verification"]["relative_error"])) <= 0.01);
  // The posterior sd of e: the lab's standard error 0.02 / sqrt(25) through the slope de_out/de_in (~1): about 0.004.
  CHECK(double(s["parameters"]["e"]["sd"]) == Approx(0.004).epsilon(0.15));
  CHECK(s["verification"]["agreement"] == "confirmed");
  CHECK(std::filesystem::exists(dir + "/out/convergence.png"));
  // Resuming re-proposes the same points from the stored runs and simulates nothing.
  auto again = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/out --jobs 2");
  CHECK(again.status == 0);
  CHECK(again.output.find("(0 run now)") != std::string::npos);
}

namespace {

// A one-factor plan for the loop's decision rule: response 20 + 5 x (coded x), target 20 +- 1 %.
CampaignPlan line_plan(bool per_run) {
  CampaignPlan plan;
  plan.rigs.push_back(PlanRig{});
  PlanResponse r;
  r.name = r.label = "y";
  r.measured = 20.0;
  r.tolerance = 0.01;
  plan.responses.push_back(r);
  plan.factors.push_back({"a", "a", 0.0, 1.0, {}});
  plan.adaptive.seed_per_run = per_run;
  return plan;
}

Observations line(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  Observations o;
  o.x = x;
  o.y = y;
  return o;
}

}  // namespace

TEST_CASE("the loop's stop rule: a noise-free run on target stops it, a lucky noisy run does not") {
  // Noise-free: runs at -1, -0.5, 0, 0.5, 1; the one at 0 hits 20 exactly.
  Eigen::MatrixXd x(5, 1);
  Eigen::VectorXd y(5);
  for (int i = 0; i < 5; ++i) {
    x(i, 0) = -1 + 0.5 * i;
    y[i] = 20 + 5 * x(i, 0);
  }
  LoopDecision clean = decide(line_plan(false), {line(x, y)}, {NoiseEstimate{}});
  CHECK(clean.met);
  CHECK(clean.chosen[0] == Approx(0.0).margin(0.02));  // 0.1 of response per 0.02 coded
  CHECK(clean.models[0].surrogate_noise_sd < 0.05);

  // Noisy: the same line plus a fixed scatter of sd ~2 at 16 points; the run at 0 lands on 20.0
  // by luck (noise 0 there), as run 11 of the cabbage loop did. The surrogate's sd of the mean
  // (~2 / sqrt(runs nearby)) is far above the tolerance 0.2, so the loop must go on.
  const double noise[16] = {1.9, -2.4, 0.8, -1.1, 2.7, -0.3, -2.2, 1.4, 0.0, -1.7, 2.1, -0.6, 1.2, -2.9, 0.5, 1.6};
  Eigen::MatrixXd xn(16, 1);
  Eigen::VectorXd yn(16);
  for (int i = 0; i < 16; ++i) {
    xn(i, 0) = -1 + 2.0 * i / 15 + (i == 8 ? -2.0 / 30 : 0.0);  // run 8 sits at coded 0 exactly
    yn[i] = 20 + 5 * xn(i, 0) + noise[i];
  }
  REQUIRE(xn(8, 0) == Approx(0.0).margin(1e-12));
  REQUIRE(yn[8] == Approx(20.0));
  for (bool per_run : {false, true}) {
    LoopDecision noisy = decide(line_plan(per_run), {line(xn, yn)}, {NoiseEstimate{}});
    const ResponseModel& m = noisy.models[0];
    INFO("per_run " << per_run << ": mean " << m.predict(noisy.chosen) << " +- " << m.predict_sd(noisy.chosen) << ", noise "
                    << m.surrogate_noise_sd);
    CHECK_FALSE(noisy.met);
    CHECK(m.predict_sd(noisy.chosen) > 0.2);
    CHECK(m.surrogate_noise_sd == Approx(1.7).margin(0.8));  // sample sd of the scatter: 1.74
    // The mean response meets the target near coded 0 (20 + 5 x = 20 within the noise's pull).
    CHECK(std::abs(m.predict(noisy.chosen) - 20.0) <= 0.2);
    // Each run its own packing: the next run repeats the best estimate to narrow its sd.
    CHECK(noisy.repeat == per_run);
    if (per_run) CHECK(noisy.next[0] == noisy.chosen[0]);
  }
}

TEST_CASE("the Gaussian process's noise stays inside the bounds its replicates give") {
  // Five unreplicated noisy runs through which a smooth curve fits exactly: free, the noise goes
  // to (nearly) zero; bounded by a pilot's interval (sd 2, 3 df: 1.13 .. 7.46), it cannot.
  Eigen::MatrixXd x(5, 1);
  Eigen::VectorXd y(5);
  const double heaps[5] = {12.7, 17.8, 16.0, 16.9, 30.0};  // the five start heaps of the cabbage loop
  for (int i = 0; i < 5; ++i) {
    x(i, 0) = -1 + 0.5 * i;
    y[i] = heaps[i];
  }
  NoiseEstimate pilot;
  pilot.sd = 2.0;
  pilot.df = 3;
  sd_interval(pilot.sd, pilot.df, pilot.low, pilot.high);
  CHECK(pilot.low == Approx(1.133).margin(0.005));  // sqrt(3 * 4 / chi2(0.975, 3) = 9.348)
  CHECK(pilot.high == Approx(7.457).margin(0.01));  // sqrt(12 / 0.2158)
  GaussianProcess bounded = fit_gaussian_process(x, y, {pilot.low, pilot.high});
  CHECK(bounded.noise_sd() >= pilot.low * 0.999);
  CHECK(bounded.noise_sd() <= pilot.high * 1.001);
}
