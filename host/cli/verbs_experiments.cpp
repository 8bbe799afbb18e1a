// `repose experiment TYPE CASE.toml`: the seeds' lab tests as simulations, measured like the lab.
// Each prints the measured quantity and writes TYPE.json plus a CSV of its time series and the
// wall forces over time (wall_forces.csv); repose also saves the heap picture (heap.png).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/cli_case.h"
#include "cli/verbs.h"
#include "experiments/drop.h"
#include "experiments/repose.h"
#include "experiments/roll.h"
#include "experiments/tilt.h"
#include "measure/heap_png.h"
#include "util/atomic_file.h"

namespace repose::cli {

namespace {

using Json = nlohmann::ordered_json;

void write_json(const std::string& path, const Json& j) {
  write_file_atomically(path, [&](std::ostream& o) { o << j.dump(2) << "\n"; });
}

void write_wall_forces(const std::string& dir, const WallForceSeries& series) {
  if (series.rows.empty()) return;
  write_file_atomically(dir + "/wall_forces.csv", [&](std::ostream& o) { series.write_csv(o); });
}

Json slope_json(const SlopeFit& s) {
  Json j;
  j["valid"] = s.valid;
  if (s.valid) {
    j["angle_deg"] = s.angle_deg;
    j["from"] = s.from;
    j["to"] = s.to;
  } else {
    j["problem"] = s.problem;
  }
  return j;
}

// Replicates 2..N of a drop: the same case with simulation.seed + k (a clump lands at a new
// random orientation each time); their rebound heights and e go into drop.json with mean and sd.
Json drop_replicates(const CaseSpec& spec, const ExperimentRunOptions& run, const DropResult& first,
                     int replicates) {
  Json list = Json::array();
  std::vector<double> e;
  for (int k = 0; k < replicates; ++k) {
    CaseSpec replicate = spec;
    replicate.seed = spec.seed + uint64_t(k);
    DropResult r = k == 0 ? first : run_drop(replicate, {run.backend, run.device, run.threads});
    e.push_back(r.restitution);
    list.push_back({{"seed", replicate.seed}, {"rebound_height", r.rebound_height}, {"restitution", r.restitution}});
    std::printf("  replicate %d (seed %llu): h = %.5g m, e = %.4f\n", k + 1,
                (unsigned long long)replicate.seed, r.rebound_height, r.restitution);
  }
  double mean = 0, var = 0;
  for (double x : e) mean += x / double(e.size());
  for (double x : e) var += (x - mean) * (x - mean) / double(std::max<size_t>(1, e.size() - 1));
  std::printf("  e over %d replicates: mean %.4f, sd %.4f\n", replicates, mean, std::sqrt(var));
  return {{"runs", list}, {"restitution_mean", mean}, {"restitution_sd", std::sqrt(var)}};
}

int run_drop_verb(const CaseSpec& spec, const std::string& case_path, const ExperimentRunOptions& run,
                  const std::string& out_dir, int replicates) {
  DropResult r = run_drop(spec, {run.backend, run.device, run.threads});
  Json j;
  j["experiment"] = "drop";
  j["case"] = case_path;
  j["drop_height"] = r.drop_height;
  j["rebound_height"] = r.rebound_height;
  j["rebound_height_exact"] = r.rebound_height_exact;
  j["restitution"] = r.restitution;
  j["impact_speed"] = r.impact_speed;
  j["contact_time"] = r.contact_time;
  j["camera_fps"] = spec.experiment.camera_fps;
  write_json(out_dir + "/drop.json", j);
  write_file_atomically(out_dir + "/trajectory.csv", [&](std::ostream& o) {
    o << "t,height\n";
    for (const auto& [t, h] : r.trajectory) o << t << "," << h << "\n";
  });
  std::printf("drop %s: H = %.4g m, rebound h = %.5g m, e = sqrt(h/H) = %.4f (impact %.3g m/s, contact %.3g ms)\n",
              spec.name.c_str(), r.drop_height, r.rebound_height, r.restitution, r.impact_speed,
              1e3 * r.contact_time);
  if (replicates > 1) {
    j["replicates"] = drop_replicates(spec, run, r, replicates);
    write_json(out_dir + "/drop.json", j);
  }
  std::printf("wrote %s/drop.json and %s/trajectory.csv\n", out_dir.c_str(), out_dir.c_str());
  return 0;
}

int run_tilt_verb(const CaseSpec& spec, const std::string& case_path, const ExperimentRunOptions& run,
                  const std::string& out_dir) {
  TiltResult r = run_tilt(spec, run);
  bool rolling = spec.experiment.type == "roll";
  const char* quantity = rolling ? "mu_r" : "mu_s";
  Json j;
  j["experiment"] = spec.experiment.type;
  j["method"] = "tilt";
  j["case"] = case_path;
  j["tilt_rate_deg_per_s"] = spec.experiment.tilt_rate_deg;
  j["onset_distance"] = spec.experiment.onset_distance;
  j["onset_angle_deg"] = r.onset_angle_deg;
  j["onset_time"] = r.onset_time;
  j[quantity] = r.tan_alpha;
  j["rolled_fraction"] = r.rolled_fraction;
  std::string name = rolling ? "roll" : "slide";
  write_json(out_dir + "/" + name + ".json", j);
  write_file_atomically(out_dir + "/trajectory.csv", [&](std::ostream& o) {
    o << "t,angle_deg,displacement\n";
    for (const auto& s : r.trajectory) o << s.time << "," << s.angle_deg << "," << s.displacement << "\n";
  });
  write_wall_forces(out_dir, r.wall_forces);
  std::printf("%s %s: the body starts to %s at alpha = %.3f deg, %s = tan(alpha) = %.4f (rolled fraction %.2f)\n",
              name.c_str(), spec.name.c_str(), rolling ? "roll" : "slide", r.onset_angle_deg, quantity, r.tan_alpha,
              r.rolled_fraction);
  std::printf("wrote %s/%s.json, trajectory.csv, wall_forces.csv\n", out_dir.c_str(), name.c_str());
  return 0;
}

int run_roll_verb(const CaseSpec& spec, const std::string& case_path, const ExperimentRunOptions& run,
                  const std::string& out_dir) {
  RollResult r = run_roll(spec, run);
  Json j;
  j["experiment"] = "roll";
  j["method"] = "incline";
  j["case"] = case_path;
  j["incline_deg"] = r.incline_deg;
  j["slope_distance"] = r.slope_distance;
  j["rolling_distance"] = r.rolling_distance;
  j["mu_r"] = r.mu_r;
  j["speed_at_foot"] = r.speed_at_foot;
  j["stop_time"] = r.stop_time;
  write_json(out_dir + "/roll.json", j);
  write_file_atomically(out_dir + "/trajectory.csv", [&](std::ostream& o) {
    o << "t,x,speed\n";
    for (const auto& s : r.trajectory) o << s.time << "," << s.x << "," << s.speed << "\n";
  });
  write_wall_forces(out_dir, r.wall_forces);
  std::printf("roll %s: beta = %.3g deg, S = %.4g m, rolling distance L = %.4g m, mu_r = S sin(beta) / (S cos(beta) + L) = %.4f\n",
              spec.name.c_str(), r.incline_deg, r.slope_distance, r.rolling_distance, r.mu_r);
  std::printf("wrote %s/roll.json, trajectory.csv, wall_forces.csv\n", out_dir.c_str());
  return 0;
}

int run_repose_verb(const CaseSpec& spec, const std::string& case_path, const ExperimentRunOptions& run,
                    const std::string& out_dir) {
  ReposeResult r = run_repose(spec, run);
  Json j;
  j["experiment"] = "repose";
  j["case"] = case_path;
  j["heap_side"] = spec.experiment.heap_side;
  j["angle_deg"] = r.angle_deg;
  j["left"] = slope_json(r.heap.left);
  j["right"] = slope_json(r.heap.right);
  j["mean_deg"] = std::isfinite(r.heap.mean_deg) ? Json(r.heap.mean_deg) : Json(nullptr);
  j["heap_height"] = r.heap.heap_height;
  j["bed_height"] = r.bed_height;
  auto profile = [](const SlopeProfile& p) {
    Json e;
    e["runout"] = p.runout;
    e["toe"] = p.toe;
    e["convexity"] = p.valid ? Json(p.convexity) : Json(nullptr);
    if (!p.valid) e["problem"] = p.problem;
    return e;
  };
  j["left_profile"] = profile(r.profile.left);
  j["right_profile"] = profile(r.profile.right);
  j["floor_z"] = r.heap.floor_z;
  j["particles_measured"] = r.particles_measured;
  j["settle_time"] = r.settle_time;
  j["largest_kinetic_energy"] = r.kinetic_energy;
  if (r.views) {
    Json v;
    v["mean_deg"] = r.views->mean_deg;
    v["sd_deg"] = r.views->sd_deg;
    v["valid_slopes"] = r.views->valid_slopes;
    v["centre"] = {r.views->centre.x, r.views->centre.y};
    Json per = Json::array();
    auto angle = [](double a) { return std::isfinite(a) ? Json(a) : Json(nullptr); };
    for (size_t k = 0; k < r.views->azimuth_deg.size(); ++k)
      per.push_back({{"azimuth_deg", r.views->azimuth_deg[k]}, {"left_deg", angle(r.views->left_deg[k])},
                     {"right_deg", angle(r.views->right_deg[k])}});
    v["per_view"] = per;
    j["views"] = v;
  }
  if (r.heap_3d) {
    Json a;
    a["mean_deg"] = r.heap_3d->mean_deg;
    a["spread_deg"] = r.heap_3d->spread_deg;
    a["min_deg"] = r.heap_3d->min_deg;
    a["max_deg"] = r.heap_3d->max_deg;
    a["valid_sectors"] = r.heap_3d->valid_sectors;
    a["centre"] = {r.heap_3d->centre.x, r.heap_3d->centre.y};
    Json sectors = Json::array();
    for (const auto& s : r.heap_3d->sectors) {
      Json e = slope_json(s.fit);
      e["from_deg"] = s.from_deg;
      e["to_deg"] = s.to_deg;
      sectors.push_back(e);
    }
    a["sectors"] = sectors;
    j["axisymmetric"] = a;
  }
  write_json(out_dir + "/repose.json", j);
  write_file_atomically(out_dir + "/energy.csv", [&](std::ostream& o) {
    o << "t,largest_kinetic_energy\n";
    for (const auto& [t, e] : r.energy) o << t << "," << e << "\n";
  });
  write_file_atomically(out_dir + "/heap.csv", [&](std::ostream& o) {
    o << "x,y,z,radius\n";
    for (const auto& s : r.spheres) o << s.centre.x << "," << s.centre.y << "," << s.centre.z << "," << s.radius << "\n";
  });
  write_wall_forces(out_dir, r.wall_forces);
  write_heap_angle_png(out_dir + "/heap.png", r.heap);
  std::printf("repose %s: angle of repose %.2f deg (left %s, right %s), heap %.3g m high, %zu particles\n",
              spec.name.c_str(), r.angle_deg,
              r.heap.left.valid ? (std::to_string(r.heap.left.angle_deg).substr(0, 5) + " deg").c_str() : "none",
              r.heap.right.valid ? (std::to_string(r.heap.right.angle_deg).substr(0, 5) + " deg").c_str() : "none",
              r.heap.heap_height, r.particles_measured);
  for (const auto& [side, p] : {std::pair{"left", &r.profile.left}, std::pair{"right", &r.profile.right}})
    std::printf("  %s side: run-out %.3g m, convexity %s\n", side, p->runout,
                p->valid ? std::to_string(p->convexity).substr(0, 6).c_str() : ("none (" + p->problem + ")").c_str());
  std::printf("  bed before the lift: %.4g m high\n", r.bed_height);
  if (r.views)
    std::printf("  %zu views around the heap: mean %.2f deg, sd %.2f deg over %d slopes (the angle)\n",
                r.views->azimuth_deg.size(), r.views->mean_deg, r.views->sd_deg, r.views->valid_slopes);
  if (r.heap_3d)
    std::printf("  3D sector fit: mean %.2f deg, spread %.2f deg over %d sectors\n", r.heap_3d->mean_deg,
                r.heap_3d->spread_deg, r.heap_3d->valid_sectors);
  std::printf("wrote %s/repose.json, heap.png, heap.csv, energy.csv, wall_forces.csv\n", out_dir.c_str());
  return 0;
}

int run_experiment(int argc, char** argv) {
  CLI::App app{"Run a virtual experiment: drop (restitution), slide (static friction on a tilting plate), "
               "roll (rolling friction: incline + floor, or tilt), repose (angle of repose of a rig)."};
  std::string type, case_path, backend = "cpu", out_dir;
  unsigned threads = 1;
  int device = -1;
  std::vector<std::string> sets;
  double height = -1;
  bool quiet = false;
  app.add_option("type", type, "experiment: drop, slide, roll, repose")
      ->required()
      ->check(CLI::IsMember({"drop", "slide", "roll", "repose"}));
  app.add_option("case", case_path, "case file (TOML) with an [experiment] table")->required();
  app.add_option("--height", height, "drop: height H of the lowest point (m); default from the case");
  app.add_option("--backend", backend, "cpu (default) or vulkan")->check(CLI::IsMember({"vulkan", "cpu"}));
  app.add_option("--threads", threads, "cpu backend threads (default 1)");
  app.add_option("--device", device, "Vulkan device index");
  app.add_option("--set", sets, "override a case key: KEY=VALUE (repeatable)");
  app.add_option("--out", out_dir, "output folder (default out/CASE_NAME)");
  app.add_flag("--quiet", quiet, "no progress output");
  int replicates = 1;
  app.add_option("--replicates", replicates,
                 "drop: N drops with seeds seed, seed+1, ... (a clump lands at a random orientation each)")
      ->check(CLI::Range(1, 1000));
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
  if (out_dir.empty()) out_dir = "out/" + spec.name;
  ExperimentRunOptions run{backend, device, threads, !quiet};
  try {
    std::filesystem::create_directories(out_dir);
    if (type == "drop") return run_drop_verb(spec, case_path, run, out_dir, replicates);
    if (type == "slide" || (type == "roll" && spec.experiment.method == "tilt"))
      return run_tilt_verb(spec, case_path, run, out_dir);
    if (type == "roll") return run_roll_verb(spec, case_path, run, out_dir);
    return run_repose_verb(spec, case_path, run, out_dir);
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}

}  // namespace

std::vector<Verb> experiment_verbs() {
  return {{"experiment", "virtual lab test: drop, slide, roll, repose (prints the result, writes JSON + CSV)",
           run_experiment}};
}

}  // namespace repose::cli
