#include "calibrate/run_job.h"

#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>

namespace repose::calibrate {

using nlohmann::json;

RunJob make_job(const CampaignPlan& plan, const RunSpec& spec) {
  RunJob job;
  job.spec = spec;
  const PlanRig& rig = plan.rigs.at(size_t(spec.rig));
  job.experiment = rig.experiment;
  job.case_path = rig.case_path;
  job.case_text = rig.case_text;
  job.overrides = run_overrides(plan, spec.rig, spec.x, spec.seed);
  job.options.backend = plan.backend;
  return job;
}

JobOutcome execute_job(const RunJob& job, int rank) {
  JobOutcome out;
  out.record.spec = job.spec;
  out.record.host = host_name();
  out.record.rank = rank;
  auto start = std::chrono::steady_clock::now();
  try {
    CaseSpec spec = load_case_from_string(job.case_text, job.case_path, job.overrides);
    out.record.responses = find_experiment(job.experiment).run(spec, job.options);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  out.record.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::string host_name() {
  char name[256] = {0};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

namespace {

json spec_to_json(const RunSpec& s) {
  return {{"id", s.id}, {"phase", s.phase}, {"point", s.point}, {"replicate", s.replicate}, {"seed", s.seed}, {"x", s.x}, {"rig", s.rig}};
}

RunSpec spec_from_json(const json& j) {
  RunSpec s;
  s.id = j.at("id");
  s.phase = j.at("phase");
  s.point = j.at("point");
  s.replicate = j.at("replicate");
  s.seed = j.at("seed");
  s.x = j.at("x").get<std::vector<double>>();
  s.rig = j.value("rig", 0);
  return s;
}

}  // namespace

std::string job_to_text(const RunJob& job) {
  json o = json::array();
  for (const auto& ov : job.overrides) o.push_back({ov.key, ov.value});
  json j = {{"spec", spec_to_json(job.spec)}, {"experiment", job.experiment}, {"case_path", job.case_path},
            {"case_text", job.case_text}, {"overrides", o}, {"backend", job.options.backend},
            {"device", job.options.device}, {"threads", job.options.threads},
            {"picture_path", job.options.picture_path}};
  return j.dump();
}

RunJob job_from_text(const std::string& text) {
  json j = json::parse(text);
  RunJob job;
  job.spec = spec_from_json(j.at("spec"));
  job.experiment = j.at("experiment");
  job.case_path = j.at("case_path");
  job.case_text = j.at("case_text");
  for (const auto& o : j.at("overrides")) job.overrides.push_back({o.at(0), o.at(1)});
  job.options.backend = j.at("backend");
  job.options.device = j.at("device");
  job.options.threads = j.at("threads");
  job.options.picture_path = j.at("picture_path");
  return job;
}

std::string outcome_to_text(const JobOutcome& out) {
  json j = {{"spec", spec_to_json(out.record.spec)}, {"responses", out.record.responses}, {"wall_s", out.record.wall_s},
            {"host", out.record.host}, {"rank", out.record.rank}, {"error", out.error}};
  return j.dump();
}

JobOutcome outcome_from_text(const std::string& text) {
  json j = json::parse(text);
  JobOutcome out;
  out.record.spec = spec_from_json(j.at("spec"));
  out.record.responses = j.at("responses").get<Responses>();
  out.record.wall_s = j.at("wall_s");
  out.record.host = j.at("host");
  out.record.rank = j.at("rank");
  out.error = j.at("error");
  return out;
}

}  // namespace repose::calibrate
