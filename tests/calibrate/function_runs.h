// A seeded noisy function behind the campaign's own code (RunSource): each run's response is a
// known mean of its parameters plus normal noise drawn from the run's packing seed, so the
// statistics (pilot, loop, posterior, verification) are tested against a known truth in
// milliseconds per campaign.
#pragma once
#include <functional>
#include <map>
#include <random>
#include <stdexcept>
#include <string>

#include "calibrate/plan.h"
#include "calibrate/run_source.h"

namespace repose::test {

class FunctionRuns : public calibrate::RunSource {
 public:
  // mean(coded point, rig); responses are named "y" on every rig.
  using Mean = std::function<double(const Eigen::VectorXd& coded, int rig)>;
  FunctionRuns(const calibrate::CampaignPlan& plan, Mean mean, double noise_sd, std::uint64_t trial)
      : plan_(plan), mean_(std::move(mean)), noise_sd_(noise_sd), trial_(trial) {}

  void run(const std::vector<calibrate::RunSpec>& specs, const std::string&) override {
    for (const auto& s : specs) {
      auto it = runs_.find(s.id);
      if (it != runs_.end()) {
        if (it->second.spec.x != s.x) throw std::runtime_error(s.id + " is held at other parameters");
        continue;
      }
      calibrate::RunRecord r;
      r.spec = s;
      std::mt19937_64 rng(trial_ * 1000003ULL + s.seed * 7919ULL + std::uint64_t(s.rig) * 104729ULL);
      std::normal_distribution<double> noise(0.0, 1.0);
      r.responses["y"] = mean_(calibrate::to_coded(plan_, s.x), s.rig) + noise_sd_ * noise(rng);
      runs_[s.id] = r;
      ++simulated;
    }
  }
  const calibrate::RunRecord* find(const std::string& id) const override {
    auto it = runs_.find(id);
    return it == runs_.end() ? nullptr : &it->second;
  }
  std::string where() const override { return "the test's function"; }

  int simulated = 0;

 private:
  const calibrate::CampaignPlan& plan_;
  Mean mean_;
  double noise_sd_;
  std::uint64_t trial_;
  std::map<std::string, calibrate::RunRecord> runs_;
};

// A plan over `factors` coded factors (actual 0 .. 1 each) with response "y" on one rig.
inline calibrate::CampaignPlan function_plan(int factors, double measured, double measured_sd, double tolerance) {
  calibrate::CampaignPlan plan;
  plan.name = "function";
  plan.rigs.push_back(calibrate::PlanRig{});
  calibrate::PlanResponse r;
  r.name = r.label = "y";
  r.measured = measured;
  r.measured_sd = measured_sd;
  r.tolerance = tolerance;
  plan.responses.push_back(r);
  for (int j = 0; j < factors; ++j) plan.factors.push_back({"x" + std::to_string(j + 1), "k" + std::to_string(j), 0.0, 1.0, {}});
  return plan;
}

}  // namespace repose::test
