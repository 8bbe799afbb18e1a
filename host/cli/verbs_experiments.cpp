// `repose experiment TYPE CASE.toml`: the seeds' lab tests as simulations, measured like the lab.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/cli_case.h"
#include "cli/verbs.h"
#include "experiments/drop.h"
#include "util/atomic_file.h"

namespace repose::cli {

namespace {

int run_experiment(int argc, char** argv) {
  CLI::App app{"Run a virtual experiment: drop (restitution from the rebound height)."};
  std::string type, case_path, backend = "cpu", out_dir;
  unsigned threads = 1;
  int device = -1;
  std::vector<std::string> sets;
  double height = -1;
  app.add_option("type", type, "experiment: drop")->required()->check(CLI::IsMember({"drop"}));
  app.add_option("case", case_path, "case file (TOML) with an [experiment] table")->required();
  app.add_option("--height", height, "drop height H of the lowest point (m); default from the case");
  app.add_option("--backend", backend, "cpu (default) or vulkan")->check(CLI::IsMember({"vulkan", "cpu"}));
  app.add_option("--threads", threads, "cpu backend threads (default 1)");
  app.add_option("--device", device, "Vulkan device index");
  app.add_option("--set", sets, "override a case key: KEY=VALUE (repeatable)");
  app.add_option("--out", out_dir, "folder for drop.json and trajectory.csv (default out/CASE_NAME)");
  CLI11_PARSE(app, argc, argv);

  std::vector<CaseOverride> extra;
  if (height > 0) extra.push_back({"experiment.drop_height", std::to_string(height)});
  auto loaded = load_case_or_report(case_path, sets, extra);
  if (!loaded) return 2;
  CaseSpec& spec = *loaded;
  if (spec.experiment.type != type) {
    std::fprintf(stderr, "%s: [experiment] type is '%s', not '%s'\n", case_path.c_str(),
                 spec.experiment.type.c_str(), type.c_str());
    return 2;
  }
  DropResult r = run_drop(spec, {backend, device, threads});
  if (out_dir.empty()) out_dir = "out/" + spec.name;
  std::filesystem::create_directories(out_dir);
  nlohmann::ordered_json j;
  j["experiment"] = "drop";
  j["case"] = case_path;
  j["drop_height"] = r.drop_height;
  j["rebound_height"] = r.rebound_height;
  j["rebound_height_exact"] = r.rebound_height_exact;
  j["restitution"] = r.restitution;
  j["impact_speed"] = r.impact_speed;
  j["contact_time"] = r.contact_time;
  j["camera_fps"] = spec.experiment.camera_fps;
  write_file_atomically(out_dir + "/drop.json", [&](std::ostream& o) { o << j.dump(2) << "\n"; });
  write_file_atomically(out_dir + "/trajectory.csv", [&](std::ostream& o) {
    o << "t,height\n";
    for (const auto& [t, h] : r.trajectory) o << t << "," << h << "\n";
  });
  std::printf("drop %s: H = %.4g m, rebound h = %.5g m, e = sqrt(h/H) = %.4f (impact %.3g m/s, contact %.3g ms)\n",
              spec.name.c_str(), r.drop_height, r.rebound_height, r.restitution, r.impact_speed,
              1e3 * r.contact_time);
  std::printf("wrote %s/drop.json and %s/trajectory.csv\n", out_dir.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace

std::vector<Verb> experiment_verbs() {
  return {{"experiment", "virtual lab test: drop (rebound height, e = sqrt(h/H))", run_experiment}};
}

}  // namespace repose::cli
