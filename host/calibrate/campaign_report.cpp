#include "calibrate/campaign_report.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "calibrate/campaign.h"
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

// The runs with every response of their rig the plan names.
void runs_table(std::ostringstream& md, const CampaignPlan& plan, const std::vector<RunRecord>& runs) {
  std::vector<int> shown;
  for (size_t i = 0; i < plan.responses.size(); ++i)
    for (const auto& r : runs)
      if (r.spec.rig == plan.responses[i].rig) {
        shown.push_back(int(i));
        break;
      }
  md << "| run | seed |";
  for (const auto& f : plan.factors) md << " " << f.name << " |";
  for (int i : shown) md << " " << plan.responses[size_t(i)].label << " | error |";
  md << " wall s | rank |\n|---|---|";
  for (size_t i = 0; i < plan.factors.size() + 2 * shown.size(); ++i) md << "---|";
  md << "---|---|\n";
  for (const auto& r : runs) {
    md << "| " << r.spec.id << " | " << r.spec.seed << " |";
    for (double x : r.spec.x) md << " " << num(x) << " |";
    for (int i : shown) {
      const PlanResponse& resp = plan.responses[size_t(i)];
      auto it = r.responses.find(resp.name);
      if (resp.rig != r.spec.rig || it == r.responses.end()) md << " | |";
      else md << " " << num(it->second) << " | " << percent((it->second - resp.measured) / resp.measured) << " |";
    }
    md << " " << num(r.wall_s, 3) << " | " << r.rank << " |\n";
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

// The plan, its rigs and responses, and what the campaign cost.
void header_section(std::ostringstream& md, const CampaignRecord& rec) {
  const CampaignPlan& plan = *rec.plan;
  const CalibrationResult& res = rec.result;
  md << "# Calibration campaign `" << plan.name << "`\n\n";
  md << "**" << verdict_line(plan, res) << ".**\n\n";
  md << "- plan: `" << plan.path << "` (hash " << plan_hash(canonical_plan_text(plan)) << "), database `" << rec.db_path << "`\n";
  for (size_t i = 0; i < plan.rigs.size(); ++i)
    md << "- " << (i == 0 ? std::string("campaign case") : "rig `" + plan.rigs[i].name + "`") << ": experiment `"
       << plan.rigs[i].experiment << "` on `" << plan.rigs[i].case_path << "`, backend " << plan.backend << "\n";
  for (const auto& r : plan.responses) {
    md << "- response `" << r.label << "` (" << (r.role == ResponseRole::calibrate ? "calibrates" : "verifies only")
       << "): measured " << num(r.measured);
    if (r.measured_sd > 0) md << ", lab sd " << num(r.measured_sd) << " over " << r.measured_n << " (standard error " << num(r.measured_se(), 4) << ")";
    else md << " (no lab sd given: taken as exact)";
    md << ", tolerance " << num(100 * r.tolerance) << " % (+-" << num(r.absolute_tolerance(), 4) << ")\n";
  }
  md << "- method: " << res.method << "; " << rec.simulations << " simulations in the database, " << num(rec.simulated_seconds, 3)
     << " s of simulation on";
  for (const auto& h : rec.hosts) md << " " << h;
  md << "\n\n## Factors\n\n| factor | case key | low | high |\n|---|---|---|---|\n";
  for (const auto& f : plan.factors) md << "| " << f.name << " | `" << f.key << "` | " << num(f.low) << " | " << num(f.high) << " |\n";
  for (const auto& rig : plan.rigs)
    if (!rig.settings.empty()) {
      md << "\nFixed for every run" << (rig.name.empty() ? "" : " on rig " + rig.name) << ":";
      for (const auto& s : rig.settings) md << " `" << s.key << " = " << s.value << "`";
      md << "\n";
    }
}

void calibrated_section(std::ostringstream& md, const CampaignPlan& plan, const CalibrationResult& res) {
  md << "\n## Calibrated parameters\n\n";
  md << (res.model_on_target ? "The model puts every calibrating response within its tolerance at the chosen point"
                             : "**The model does not put every calibrating response within its tolerance** at the chosen point")
     << ". Whether the target is reached is the verification's to say (below).\n\n";
  md << "| parameter | chosen | 90 % credible interval | posterior median | posterior sd | d" << plan.primary().label
     << "/dx | model within tolerance for |\n|---|---|---|---|---|---|---|\n";
  for (const auto& p : res.parameters) {
    md << "| " << p.name << " | " << num(p.value) << " | ";
    if (p.has_posterior)
      md << num(p.low, 4) << " .. " << num(p.high, 4) << (p.identified ? "" : " (not identified)") << " | " << num(p.median, 4)
         << " | " << num(p.sd, 3);
    else md << "none: " << res.method << " fits no model | | ";
    md << " | " << num(p.slope, 4) << " | " << num(p.set_low) << " .. " << num(p.set_high) << " |\n";
  }
  if (res.posterior.computed) {
    md << "\nThe posterior (flat prior over the factor box) weighs each parameter set by how well the model's mean response "
          "meets the measured value, given the lab's standard error and the model's own uncertainty (the runs' noise averaged); "
          "the credible interval holds 90 % of each parameter's marginal. The joint 90 % region fills "
       << num(100 * res.posterior.region_fraction, 3) << " % of the box.";
    if (!res.ridge_text.empty()) md << " " << res.ridge_text;
    md << "\n";
  }
  md << "\n## Run-to-run noise (from replicates)\n\n| response | noise sd | df | 95 % interval | model at the chosen point |\n"
     << "|---|---|---|---|---|\n";
  for (const auto& m : res.models) {
    md << "| " << plan.responses[size_t(m.response)].label << " | ";
    if (m.noise.known()) md << num(m.noise.sd, 4) << " | " << m.noise.df << " | " << num(m.noise.low, 4) << " .. " << num(m.noise.high, 4);
    else md << "unknown: nothing replicated | 0 | ";
    md << " | " << num(m.predicted) << " +- " << num(m.predicted_sd, 3) << " |\n";
  }
}

void verification_section(std::ostringstream& md, const CampaignPlan& plan, const CalibrationResult& res) {
  md << "\n## Verification\n\n";
  if (res.checks.empty()) {
    md << "No verification runs (verification.runs = 0): the calibrated parameters are not checked, so the target is not reached.\n";
    return;
  }
  md << "Each verified response's mean, with its standard error (the noise sd over the square root of the runs), against the "
        "measured value with the lab's standard error: **confirmed** when the difference is within the tolerance and its "
        "standard error too, **contradicted** when the difference exceeds the tolerance by more than two standard errors, "
        "**inconclusive** otherwise.\n\n";
  for (const auto& c : res.checks) {
    md << "- " << check_text(plan, c) << "\n";
  }
  for (const auto& c : res.checks) {
    md << "\n";
    runs_table(md, plan, c.runs);
  }
}

// The adaptive loop's runs in order, with the expected improvement that proposed each.
void loop_section(std::ostringstream& md, const CampaignPlan& plan, const CalibrationResult& res, const AdaptiveOutcome& loop) {
  md << "\n## Adaptive loop\n\n";
  if (!loop.pilot.empty())
    md << "Noise pilot: " << loop.pilot.size() << " runs at " << plan.adaptive.pilot_points << " point(s), each its own seed. ";
  md << loop.initial << " space-filling runs (Halton), then one proposal at a time.";
  md << (plan.adaptive.seed_per_run ? " Each run packs with its own seed." : " Every run packs with the same seed.");
  if (loop.simulations_to_target > 0)
    md << " The surrogate met the tolerance after loop run " << loop.simulations_to_target
       << " (its means within the tolerance and known to within it).";
  else md << " The surrogate did not meet the tolerance within the budget of " << plan.adaptive.budget << ".";
  md << " At the chosen point it expects " << plan.primary().label << " = " << num(res.primary().predicted) << " +- "
     << num(res.primary().predicted_sd, 3) << ".";
  md << "\n\n| # | ";
  for (const auto& f : plan.factors) md << f.name << " | ";
  md << plan.primary().label << " | error | expected improvement |\n|---|";
  for (size_t i = 0; i <= plan.factors.size(); ++i) md << "---|";
  md << "---|---|\n";
  for (size_t i = 0; i < loop.steps.size(); ++i) {
    const auto& s = loop.steps[i];
    md << "| " << i + 1 << " | ";
    for (double x : s.run.spec.x) md << num(x) << " | ";
    md << num(s.values[0]) << " | " << percent(s.relative_error) << " | "
       << (int(i) < loop.initial ? "(start)" : num(s.expected_improvement, 3)) << " |\n";
  }
  if (!loop.pilot.empty()) {
    md << "\nNoise pilot runs:\n\n";
    runs_table(md, plan, loop.pilot);
  }
  for (const auto& round : loop.rounds) {
    if (round.budget_end)
      md << "\nAn earlier, smaller budget ended after loop run " << round.loop_runs
         << " and its verification did not confirm the choice; the raised budget went on with its runs in the surrogate's data:\n\n";
    else
      md << "\nThe surrogate met the tolerance after loop run " << round.loop_runs
         << " and the verification there did not confirm it, so its runs joined the surrogate's data and the loop went on:\n\n";
    for (const auto& c : round.checks) md << "- " << check_text(plan, c) << "\n";
    if (!round.checks.empty()) {
      md << "\n";
      runs_table(md, plan, round.checks.front().runs);
    }
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
    runs_table(md, plan, res.primary().runs);
  }
  md << "\n## Model\n\n```\n" << res.model_text << "```\n\n## Figures\n\n";
  for (const auto& f : rec.figures) md << "![" << f.file << "](" << f.file << ")\n\n" << f.caption << "\n\n";
  return md.str();
}

// What produced the campaign: the base case, the plan's fixed settings as overrides, the hosts.
Provenance campaign_provenance(const CampaignRecord& rec) {
  const CampaignPlan& plan = *rec.plan;
  Provenance prov;
  prov.case_path = plan.rigs[0].case_path;
  prov.case_hash = fnv1a_hex(plan.rigs[0].case_identity);
  for (const auto& setting : plan.rigs[0].settings) prov.overrides.push_back(setting.key + "=" + setting.value);
  prov.seed = plan.base_seed;
  prov.backend = plan.backend;
  for (const auto& h : rec.hosts) prov.device += (prov.device.empty() ? "" : ", ") + h;  // host:rank of the runs
  return prov;
}

nlohmann::ordered_json optional_number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json noise_json(const NoiseEstimate& n) {
  if (!n.known()) return {{"sd", nullptr}, {"df", 0}, {"low", nullptr}, {"high", nullptr}};
  return {{"sd", n.sd}, {"df", n.df}, {"low", n.low}, {"high", optional_number(n.high)}};
}

nlohmann::ordered_json check_json(const CampaignPlan& plan, const ResponseCheck& c) {
  const PlanResponse& r = plan.responses[size_t(c.response)];
  return {{"response", r.label}, {"agreement", agreement_name(c.agreement)}, {"mean", c.mean}, {"sd", c.run_sd},
          {"se", optional_number(c.se)}, {"measured", r.measured}, {"measured_se", c.measured_se},
          {"difference", c.difference}, {"difference_se", optional_number(c.difference_se)},
          {"relative_error", c.relative_error(r.measured)}, {"tolerance", c.tolerance}, {"noise", noise_json(c.noise)},
          {"runs_needed", c.runs_needed}, {"runs", runs_json(plan, c.runs)}};
}

nlohmann::ordered_json parameters_json(const CalibrationResult& res) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& p : res.parameters) {
    nlohmann::ordered_json e = {{"value", p.value}, {"slope", p.slope}, {"set_low", p.set_low}, {"set_high", p.set_high}};
    if (p.has_posterior) {
      e["credible_low"] = p.low;
      e["credible_high"] = p.high;
      e["median"] = p.median;
      e["sd"] = p.sd;
      e["identified"] = p.identified;
    }
    j[p.name] = e;
  }
  return j;
}

nlohmann::ordered_json summary_json(const CampaignRecord& rec) {
  const CampaignPlan& plan = *rec.plan;
  const CalibrationResult& res = rec.result;
  nlohmann::ordered_json j;
  j["campaign"] = plan.name;
  j["plan"] = plan.path;
  j["plan_hash"] = plan_hash(canonical_plan_text(plan));
  j["database"] = rec.db_path;
  j["experiment"] = plan.rigs[0].experiment;
  j["method"] = res.method;
  j["response"] = plan.primary().label;
  j["measured"] = plan.primary().measured;
  j["measured_sd"] = plan.primary().measured_sd;
  j["measured_se"] = plan.primary().measured_se();
  j["tolerance"] = plan.primary().tolerance;
  j["target_reached"] = res.target_reached;
  j["verdict"] = verdict_line(plan, res);
  j["model_on_target"] = res.model_on_target;
  j["predicted"] = res.primary().predicted;
  j["predicted_sd"] = res.primary().predicted_sd;
  j["simulations"] = rec.simulations;
  if (rec.loop) {
    j["simulations_to_target"] = rec.loop->simulations_to_target;
    j["loop_runs"] = int(rec.loop->steps.size());
    j["pilot_runs"] = int(rec.loop->pilot.size());
    nlohmann::ordered_json rounds = nlohmann::ordered_json::array();
    for (const auto& round : rec.loop->rounds) {
      nlohmann::ordered_json r{{"after_loop_run", round.loop_runs},
                               {"why", round.budget_end ? "an earlier budget ended here" : "the surrogate met the tolerance"},
                               {"checks", nlohmann::ordered_json::array()}};
      for (const auto& c : round.checks) r["checks"].push_back(check_json(plan, c));
      rounds.push_back(r);
    }
    j["verifications_fed_back"] = rounds;
  }
  j["parameters"] = parameters_json(res);
  for (const auto& m : res.models) j["noise"][plan.responses[size_t(m.response)].label] = noise_json(m.noise);
  if (res.posterior.computed) {
    nlohmann::ordered_json ridge = nlohmann::ordered_json::object();
    for (size_t f = 0; f < plan.factors.size(); ++f) ridge[plan.factors[f].name] = res.posterior.ridge[int(f)];
    j["posterior"] = {{"region_fraction", res.posterior.region_fraction}, {"ridge_direction_coded", ridge},
                      {"ridge_sd_coded", res.posterior.ridge_sd}, {"across_sd_coded", res.posterior.across_sd},
                      {"text", res.ridge_text}};
  }
  // The first verified response as before; every one under "verifications".
  j["verification"] = res.checks.empty() ? nlohmann::ordered_json(nullptr) : check_json(plan, res.checks[0]);
  j["verifications"] = nlohmann::ordered_json::array();
  for (const auto& c : res.checks) j["verifications"].push_back(check_json(plan, c));
  j["model_runs"] = runs_json(plan, res.primary().runs);
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
