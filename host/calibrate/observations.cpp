#include "calibrate/observations.h"

#include <stdexcept>

namespace repose::calibrate {

std::string rig_run_id(const CampaignPlan& plan, const std::string& id, int rig) {
  return rig == 0 ? id : id + "@" + plan.rigs.at(size_t(rig)).name;
}

std::vector<RunSpec> on_rigs(const CampaignPlan& plan, const std::vector<RunSpec>& points, const std::vector<int>& rigs) {
  std::vector<RunSpec> out;
  for (const auto& p : points)
    for (int rig : rigs) {
      RunSpec s = p;
      s.id = rig_run_id(plan, p.id, rig);
      s.rig = rig;
      out.push_back(s);
    }
  return out;
}

double response_value(const RunRecord& run, const std::string& name) {
  auto it = run.responses.find(name);
  if (it == run.responses.end()) throw std::runtime_error("run " + run.spec.id + " has no response '" + name + "'");
  return it->second;
}

Observations observe(const CampaignPlan& plan, const RunSource& source, const std::vector<RunSpec>& points, int response) {
  const PlanResponse& r = plan.responses.at(size_t(response));
  Observations obs;
  obs.response = response;
  obs.x.resize(int(points.size()), int(plan.factors.size()));
  obs.y.resize(int(points.size()));
  for (size_t i = 0; i < points.size(); ++i) {
    const std::string id = rig_run_id(plan, points[i].id, r.rig);
    const RunRecord* run = source.find(id);
    if (!run) throw std::runtime_error(id + " is missing from " + source.where());
    obs.x.row(int(i)) = to_coded(plan, run->spec.x).transpose();
    obs.y[int(i)] = response_value(*run, r.name);
    obs.runs.push_back(*run);
  }
  return obs;
}

std::vector<std::vector<double>> replicate_groups(const Observations& obs) {
  std::vector<std::vector<double>> groups;
  std::vector<int> first;  // a row holding each group's point
  for (int i = 0; i < obs.x.rows(); ++i) {
    size_t g = 0;
    while (g < first.size() && obs.x.row(first[g]) != obs.x.row(i)) ++g;
    if (g == first.size()) {
      first.push_back(i);
      groups.emplace_back();
    }
    groups[g].push_back(obs.y[i]);
  }
  return groups;
}

}  // namespace repose::calibrate
