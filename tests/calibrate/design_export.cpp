// A campaign's runs as Design-Expert imports them (calibrate/design_export.h): its column layout
// (Std, Run, "Factor N L:name (unit)", "Response N name (unit)"), actual values in run order.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "calibrate/design_export.h"

using namespace repose::calibrate;

TEST_CASE("the campaign's runs export as a Design-Expert table", "[calibrate][export]") {
  CampaignPlan plan;
  PlanResponse response;
  response.name = "rebound_height";
  plan.responses = {response};
  plan.factors = {{"e", "interaction.0.restitution", 0.4, 0.44, {}},
                  {"G", "material.0.shear_modulus", 1e6, 2e6, {}}};
  ResponseModel model;  // the first calibrating response and its runs
  std::vector<RunRecord>& runs = model.runs;
  runs.resize(2);
  runs[0].spec.point = 3;
  runs[0].spec.x = {0.42, 1.5e6};
  runs[0].responses = {{"rebound_height", 0.0812}, {"contact_time", 0.014}};
  runs[1].spec.point = 0;
  runs[1].spec.x = {0.4, 1e6};
  runs[1].responses = {{"rebound_height", 0.0733}};
  std::string path = (std::filesystem::temp_directory_path() / "repose_test_design_expert.csv").string();
  write_design_expert_csv(plan, model, path);
  std::ifstream in(path);
  std::string header, first, second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  CHECK(header == "Std,Run,Factor 1 A:e,Factor 2 B:G (Pa),Response 1 rebound_height (m),Response 2 contact_time (s)");
  CHECK(first == "4,1,0.42,1500000,0.0812,0.014");
  CHECK(second == "1,2,0.4,1000000,0.0733,");  // a response the run did not report stays empty
  std::filesystem::remove(path);
}
