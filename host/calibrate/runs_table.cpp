#include "calibrate/runs_table.h"

#include <set>

#include "stats/csv_table.h"
#include "util/atomic_file.h"
#include "util/number_text.h"

namespace repose::calibrate {

namespace {

stats::Table rig_table(const CampaignPlan& plan, const std::map<std::string, RunRecord>& runs, int rig) {
  std::set<std::string> responses;
  for (const auto& [id, r] : runs)
    if (r.spec.rig == rig)
      for (const auto& [name, v] : r.responses) responses.insert(name);
  stats::Table t;
  t.columns = {"run", "phase", "seed"};
  for (const auto& f : plan.factors) t.columns.push_back(f.name);
  for (const auto& f : plan.factors) t.columns.push_back(f.name + "_coded");
  t.columns.insert(t.columns.end(), responses.begin(), responses.end());
  t.columns.push_back("wall_s");
  for (const auto& [id, r] : runs) {
    if (r.spec.rig != rig) continue;
    std::vector<std::string> row = {id, r.spec.phase, std::to_string(r.spec.seed)};
    for (double x : r.spec.x) row.push_back(exact_number(x));
    for (size_t j = 0; j < plan.factors.size(); ++j) row.push_back(exact_number(plan.factors[j].to_coded(r.spec.x[j])));
    for (const auto& name : responses) {
      auto it = r.responses.find(name);
      row.push_back(it == r.responses.end() ? "" : exact_number(it->second));
    }
    row.push_back(format_g(r.wall_s, 4));
    t.cells.push_back(row);
  }
  return t;
}

}  // namespace

void write_runs_tables(const CampaignPlan& plan, const std::map<std::string, RunRecord>& runs, const std::string& dir) {
  for (size_t rig = 0; rig < plan.rigs.size(); ++rig) {
    stats::Table t = rig_table(plan, runs, int(rig));
    if (t.cells.empty()) continue;
    const std::string file = rig == 0 ? "runs.csv" : "runs_" + plan.rigs[rig].name + ".csv";
    const std::string what = rig == 0 ? "the campaign's case " : "rig " + plan.rigs[rig].name + " ";
    std::string names, ranges;
    for (const auto& f : plan.factors) {
      names += (names.empty() ? "" : ",") + f.name;
      ranges += (ranges.empty() ? "" : ",") + exact_number(f.low) + ":" + exact_number(f.high);
    }
    write_file_atomically(dir + "/" + file,
                          stats::format_csv(t, {"repose calibrate " + plan.name + ": every run on " + what + "(" +
                                                    plan.rigs[rig].case_path + "), one per row",
                                                "fit with: repose fit " + file + " --response NAME --factors " + names +
                                                    " --coded " + ranges}));
  }
}

}  // namespace repose::calibrate
