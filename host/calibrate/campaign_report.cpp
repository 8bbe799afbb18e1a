#include "calibrate/campaign_report.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/provenance.h"
#include "util/atomic_file.h"
#include "util/hash.h"
#include "util/number_text.h"

namespace repose::calibrate {

namespace {

std::string num(double v, int digits = 6) { return std::isinf(v) ? "inf" : format_g(v, digits); }

std::string percent(double fraction) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%+.2f %%", 100 * fraction);
  return buf;
}

void runs_table(std::ostringstream& md, const CampaignPlan& plan, const std::vector<RunRecord>& runs) {
  md << "| run | seed |";
  for (const auto& f : plan.factors) md << " " << f.name << " |";
  md << " " << plan.response << " | error | wall s | rank |\n|---|---|";
  for (size_t i = 0; i < plan.factors.size(); ++i) md << "---|";
  md << "---|---|---|---|\n";
  for (const auto& r : runs) {
    double y = r.responses.at(plan.response);
    md << "| " << r.spec.id << " | " << r.spec.seed << " |";
    for (double x : r.spec.x) md << " " << num(x) << " |";
    md << " " << num(y) << " | " << percent((y - plan.measured) / plan.measured) << " | " << num(r.wall_s, 3) << " | "
       << r.rank << " |\n";
  }
}

nlohmann::ordered_json runs_json(const CampaignPlan& plan, const std::vector<RunRecord>& runs) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const auto& r : runs) {
    nlohmann::ordered_json j;
    j["id"] = r.spec.id;
    j["seed"] = r.spec.seed;
    for (size_t i = 0; i < plan.factors.size(); ++i) j["factors"][plan.factors[i].name] = r.spec.x[i];
    j["responses"] = r.responses;
    a.push_back(j);
  }
  return a;
}

// The plan, the experiment and what the campaign cost.
void header_section(std::ostringstream& md, const CampaignRecord& rec) {
  const CampaignPlan& plan = *rec.plan;
  const CalibrationResult& res = rec.result;
  const double tol = plan.absolute_tolerance();
  md << "# Calibration campaign `" << plan.name << "`\n\n";
  md << "- plan: `" << plan.path << "` (hash " << plan_hash(canonical_plan_text(plan)) << "), database `" << rec.db_path << "`\n";
  md << "- experiment `" << plan.experiment << "` on the base case `" << plan.case_path << "`, backend " << plan.backend << "\n";
  md << "- response `" << plan.response << "`: measured " << num(plan.measured);
  if (plan.measured_sd > 0) md << " +- " << num(plan.measured_sd) << " (sd)";
  md << ", tolerance " << num(100 * plan.tolerance) << " % (+-" << num(tol) << ")\n";
  md << "- method: " << res.method << "; " << rec.simulations << " simulations, " << num(rec.simulated_seconds, 3)
     << " s of simulation on";
  for (const auto& h : rec.hosts) md << " " << h;
  md << "\n\n## Factors\n\n| factor | case key | low | high |\n|---|---|---|---|\n";
  for (const auto& f : plan.factors) md << "| " << f.name << " | `" << f.key << "` | " << num(f.low) << " | " << num(f.high) << " |\n";
  if (!plan.settings.empty()) {
    md << "\nFixed for every run:";
    for (const auto& s : plan.settings) md << " `" << s.key << " = " << s.value << "`";
    md << "\n";
  }
}

void calibrated_section(std::ostringstream& md, const CampaignPlan& plan, const CalibrationResult& res) {
  md << "\n## Calibrated parameters\n\n";
  md << (res.target_reached ? "The target is reached" : "**The target is not reached** within the tolerance")
     << "; model prediction at the chosen point: " << num(res.predicted) << ".\n\n";
  md << "| parameter | calibrated | uncertainty (1 sd) | d" << plan.response << "/dx | range meeting the target (others free) |\n"
     << "|---|---|---|---|---|\n";
  for (const auto& p : res.parameters)
    md << "| " << p.name << " | " << num(p.value) << " | " << num(p.uncertainty, 3) << " | " << num(p.slope, 4) << " | "
       << (res.target_reached ? num(p.set_low) + " .. " + num(p.set_high) : std::string("none: out of reach")) << " |\n";
  md << "\nUncertainty: sigma_y / |slope| with sigma_y = sqrt(measured_sd^2 + replicate_sd^2) = " << num(res.sigma_response, 4)
     << " (measured sd " << num(plan.measured_sd, 4) << ", replicate sd " << num(res.replicate_sd, 4) << " on "
     << res.replicate_df << " df from runs that differ only by their packing seed), each parameter moved alone.";
  if (res.replicate_df > 0 && res.replicate_sd == 0)
    md << " Replicates gave identical responses: this experiment does not depend on the packing seed.";
  if (res.sigma_response == 0) md << " With no noise and no measured sd the uncertainty is zero; the range column is what the tolerance allows.";
  md << " The range column lists every sampled parameter set whose predicted response is within the tolerance: one measured value is "
        "met by a whole curve or surface of parameter sets.\n";
}

void verification_section(std::ostringstream& md, const CampaignPlan& plan, const CalibrationResult& res) {
  md << "\n## Verification\n\n";
  if (res.verification.empty()) md << "No verification runs (verification.runs = 0).\n";
  else {
    md << "Mean " << num(res.verification_mean) << ", sd " << num(res.verification_sd, 4) << " over " << res.verification.size()
       << " runs; relative error against the measured value " << percent(res.verification_error)
       << (std::abs(res.verification_error) <= plan.tolerance ? " (within" : " (outside") << " the tolerance).\n\n";
    runs_table(md, plan, res.verification);
  }
}

// The adaptive loop's runs in order, with the expected improvement that proposed each.
void loop_section(std::ostringstream& md, const CampaignPlan& plan, const CalibrationResult& res,
                  const AdaptiveOutcome& loop) {
  md << "\n## Adaptive loop\n\n" << loop.initial << " space-filling runs (Halton), then one proposal at a time.";
  md << (plan.adaptive.seed_per_run ? " Each run packs with its own seed." : " Every run packs with the same seed.");
  if (loop.simulations_to_target > 0)
    md << " The target was met after simulation " << loop.simulations_to_target
       << " (the surrogate's mean within the tolerance and known to within it).";
  else md << " The target was not met within the budget of " << plan.adaptive.budget << ".";
  md << " At the chosen point the surrogate expects " << plan.response << " = " << num(res.predicted) << " +- "
     << num(res.predicted_sd, 3) << "; run-to-run noise sd " << num(res.run_noise_sd, 3) << ".";
  md << "\n\n| # | ";
  for (const auto& f : plan.factors) md << f.name << " | ";
  md << plan.response << " | error | expected improvement |\n|---|";
  for (size_t i = 0; i <= plan.factors.size(); ++i) md << "---|";
  md << "---|---|\n";
  for (size_t i = 0; i < loop.steps.size(); ++i) {
    const auto& s = loop.steps[i];
    md << "| " << i + 1 << " | ";
    for (double x : s.run.spec.x) md << num(x) << " | ";
    md << num(s.run.responses.at(plan.response)) << " | " << percent(s.relative_error) << " | "
       << (int(i) < loop.initial ? "(start)" : num(s.expected_improvement, 3)) << " |\n";
  }
}

std::string report_markdown(const CampaignRecord& rec) {
  const CampaignPlan& plan = *rec.plan;
  const CalibrationResult& res = rec.result;
  std::ostringstream md;
  header_section(md, rec);
  calibrated_section(md, plan, res);
  verification_section(md, plan, res);
  if (rec.loop) {
    loop_section(md, plan, res, *rec.loop);
  } else {
    md << "\n## Design runs\n\n";
    runs_table(md, plan, rec.model_runs);
  }
  md << "\n## Model\n\n```\n" << res.model_text << "```\n\n## Figures\n\n";
  for (const auto& f : rec.figures) md << "![" << f.file << "](" << f.file << ")\n\n" << f.caption << "\n\n";
  return md.str();
}

// What produced the campaign: the base case, the plan's fixed settings as overrides, the hosts.
Provenance campaign_provenance(const CampaignRecord& rec) {
  const CampaignPlan& plan = *rec.plan;
  Provenance prov;
  prov.case_path = plan.case_path;
  prov.case_hash = fnv1a_hex(plan.case_identity);
  for (const auto& setting : plan.settings) prov.overrides.push_back(setting.key + "=" + setting.value);
  prov.seed = plan.base_seed;
  prov.backend = plan.backend;
  for (const auto& h : rec.hosts) prov.device += (prov.device.empty() ? "" : ", ") + h;  // host:rank of the runs
  return prov;
}

nlohmann::ordered_json summary_json(const CampaignRecord& rec) {
  const CampaignPlan& plan = *rec.plan;
  const CalibrationResult& res = rec.result;
  nlohmann::ordered_json j;
  j["campaign"] = plan.name;
  j["plan"] = plan.path;
  j["plan_hash"] = plan_hash(canonical_plan_text(plan));
  j["database"] = rec.db_path;
  j["experiment"] = plan.experiment;
  j["method"] = res.method;
  j["response"] = plan.response;
  j["measured"] = plan.measured;
  j["measured_sd"] = plan.measured_sd;
  j["tolerance"] = plan.tolerance;
  j["target_reached"] = res.target_reached;
  j["predicted"] = res.predicted;
  j["simulations"] = rec.simulations;
  if (rec.loop) {
    j["simulations_to_target"] = rec.loop->simulations_to_target;
    j["loop_runs"] = int(rec.loop->steps.size());
    j["predicted_sd"] = res.predicted_sd;
    j["run_noise_sd"] = res.run_noise_sd;
  }
  // No range meets an unreachable target, and no verification says nothing: null, not numbers.
  auto reached = [&](double v) { return res.target_reached ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
  for (const auto& p : res.parameters)
    j["parameters"][p.name] = {{"value", p.value}, {"uncertainty", std::isfinite(p.uncertainty) ? nlohmann::ordered_json(p.uncertainty) : nlohmann::ordered_json(nullptr)},
                               {"slope", p.slope}, {"set_low", reached(p.set_low)}, {"set_high", reached(p.set_high)}};
  j["replicate_sd"] = res.replicate_sd;
  j["replicate_df"] = res.replicate_df;
  j["sigma_response"] = res.sigma_response;
  auto verified = [&](double v) { return res.verification.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(v); };
  j["verification"] = {{"mean", verified(res.verification_mean)}, {"sd", verified(res.verification_sd)},
                       {"relative_error", verified(res.verification_error)}, {"runs", runs_json(plan, res.verification)}};
  j["model_runs"] = runs_json(plan, rec.model_runs);
  j["provenance"] = provenance_json(campaign_provenance(rec));
  for (const auto& f : rec.figures) j["figures"].push_back(f.file);
  return j;
}

}  // namespace

void write_campaign_report(const CampaignRecord& rec, const std::string& dir) {
  write_file_atomically(dir + "/report.md", report_markdown(rec));
  write_file_atomically(dir + "/summary.json", summary_json(rec).dump(2) + "\n");
}

}  // namespace repose::calibrate
