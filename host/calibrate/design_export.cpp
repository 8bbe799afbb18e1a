#include "calibrate/design_export.h"

#include <set>
#include <sstream>

#include "stats/design_figures.h"
#include "stats/model_terms.h"
#include "util/atomic_file.h"
#include "util/number_text.h"
#include "util/units.h"

namespace repose::calibrate {

namespace {

std::string with_unit(const std::string& name, const std::string& key) {
  std::string unit = quantity_unit(key);
  return unit.empty() ? name : name + " (" + unit + ")";
}

// A CSV cell: quoted when it holds a comma or a quote.
std::string cell(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

void write_design_expert_csv(const CampaignPlan& plan, const ResponseModel& model, const std::string& path) {
  const std::vector<RunRecord>& runs = model.runs;
  const std::string& response = plan.responses[size_t(model.response)].name;
  std::vector<std::string> responses = {response};
  std::set<std::string> seen = {response};
  for (const auto& r : runs)
    for (const auto& [name, value] : r.responses)
      if (seen.insert(name).second) responses.push_back(name);
  std::ostringstream out;
  out << "Std,Run";
  for (size_t i = 0; i < plan.factors.size(); ++i)
    out << "," << cell("Factor " + std::to_string(i + 1) + " " + stats::factor_letter(int(i)) + ":" +
                       with_unit(plan.factors[i].name, plan.factors[i].key));
  for (size_t i = 0; i < responses.size(); ++i)
    out << "," << cell("Response " + std::to_string(i + 1) + " " + with_unit(responses[i], responses[i]));
  out << "\n";
  for (size_t k = 0; k < runs.size(); ++k) {
    const RunRecord& r = runs[k];
    out << r.spec.point + 1 << "," << k + 1;
    for (double x : r.spec.x) out << "," << format_g(x, 10);
    for (const auto& name : responses) {
      auto found = r.responses.find(name);
      out << "," << (found == r.responses.end() ? "" : format_g(found->second, 10));
    }
    out << "\n";
  }
  write_file_atomically(path, out.str());
}

bool write_surface_figure(const CampaignPlan& plan, const CalibrationResult& res, const ResponseModel& model,
                          const std::string& dir, Figure& figure) {
  if (plan.factors.size() < 2 || !model.predict) return false;
  const std::string& response = plan.responses[size_t(model.response)].name;
  const PlanFactor &fa = plan.factors[0], &fb = plan.factors[1];
  auto coded = [](const PlanFactor& f, double a) { return (a - 0.5 * (f.low + f.high)) / (0.5 * (f.high - f.low)); };
  auto actual = [](const PlanFactor& f, double c) { return 0.5 * (f.low + f.high) + c * 0.5 * (f.high - f.low); };
  stats::SurfacePicture s;
  s.f = [&](double a, double b) {
    Eigen::VectorXd c = res.chosen_coded;
    c[0] = coded(fa, a);
    c[1] = coded(fb, b);
    return model.predict(c);
  };
  double e = res.coded_extent;
  s.a0 = actual(fa, -e), s.a1 = actual(fa, e), s.b0 = actual(fb, -e), s.b1 = actual(fb, e);
  s.a_label = with_unit(fa.name, fa.key);
  s.b_label = with_unit(fb.name, fb.key);
  s.z_label = with_unit(response, response);
  s.title = response + ": the model over " + fa.name + " and " + fb.name;
  for (const auto& r : model.runs)
    if (auto found = r.responses.find(response); found != r.responses.end())
      s.runs.push_back({r.spec.x[0], r.spec.x[1], found->second});
  stats::write_surface_3d(s, dir + "/surface_3d.png");
  std::string others = plan.factors.size() > 2 ? " (other factors at their calibrated values)" : "";
  figure = {"surface_3d.png", "The response surface of " + response + " over " + fa.name + " and " + fb.name + others +
                                  " in 3D, coloured by height; dots the runs at their simulated response."};
  return true;
}

}  // namespace repose::calibrate
