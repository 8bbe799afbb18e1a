// `repose devices`, `repose run`: the engine's verbs (`repose bench`: verbs_bench.cpp).
#include <CLI/CLI.hpp>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli/cli_case.h"
#include "cli/cli_checks.h"
#include "cli/verbs.h"
#include "engine/backend_factory.h"
#include "engine/memory_need.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "io/case_run.h"
#include "io/output_dir.h"
#include "vk/context.h"

namespace repose::cli {

namespace {

namespace fs = std::filesystem;

int run_devices(int argc, char** argv) {
  CLI::App app{"List the Vulkan devices, and the backend `repose run` and the experiments use by default, and why."};
  REPOSE_PARSE(app, argc, argv);
  auto devices = vk::Context::list_devices();
  if (devices.empty()) {
    std::fprintf(stderr, "no Vulkan device found (install mesa-vulkan-drivers for lavapipe)\n");
    return 1;
  }
  int chosen = vk::Context::default_device_index(devices);
  for (const auto& d : devices)
    std::printf("%s [%u] %s (%s; %s; %.1f GiB device-local)\n", int(d.index) == chosen ? "*" : " ",
                d.index, d.name.c_str(), d.type.c_str(), d.driver.c_str(),
                d.device_local_bytes / 1073741824.0);
  for (const auto& d : devices) std::printf("  [%u] limits: %s\n", d.index, d.limits_text().c_str());
  std::printf("* = the device of --backend vulkan (--device N chooses another)\n");
  BackendChoice c = choose_backend(devices);
  std::printf("default backend: %s%s: %s\n", c.backend.c_str(),
              c.backend == "cpu" ? (" with " + std::to_string(std::max(1u, std::thread::hardware_concurrency())) +
                                    " threads").c_str()
                                 : (" on device [" + std::to_string(c.device) + "]").c_str(),
              c.reason.c_str());
  return 0;
}

int run_case(int argc, char** argv) {
  CLI::App app{"Run a case file: progress on stderr; VTK frames, wall forces and summary.json in --out."};
  std::string case_path;
  CaseRunOptions o;
  uint64_t steps = 0;
  double sim_time = 0;
  app.add_option("case", case_path, "case file (TOML)")->required();
  app.add_option("--backend", o.backend, "auto (default: a hardware GPU, else cpu; see `repose devices`), vulkan or cpu")
      ->check(CLI::IsMember({"auto", "vulkan", "cpu"}));
  app.add_option("--device", o.device, "Vulkan device index (see `repose devices`)")->check(whole_number(0, 63));
  app.add_option("--threads", o.threads, "cpu backend threads (default: all cores)")->check(thread_count());
  auto* steps_opt = app.add_option("--steps", steps, "run this many steps instead of the case's end time (with --restart: this many more)")
                        ->check(whole_number(0, 1000000000000LL));
  auto* time_opt = app.add_option("--time", sim_time, "run this much simulated time, s (with --restart: this much more)")
                       ->excludes(steps_opt)->check(finite_positive());
  app.add_option("--out", o.out_dir, "output folder, new or empty (default out/CASE_NAME)")
      ->check(non_empty_path());
  app.add_flag("--overwrite", o.overwrite, "delete what --out holds before the run");
  app.add_option("--state-out", o.state_out, "write the final state here (docs/state-format.md)")
      ->check(non_empty_path());
  app.add_option("--restart", o.restart,
                 "continue from a state file (--state-out or a checkpoint): same bytes as a run that never stopped")
      ->check(non_empty_path());
  app.add_option("--set", o.overrides, "override a case key: KEY=VALUE (repeatable)");
  app.add_option("--variant", o.variant,
                 "kernel variant: contact|rows, lean|full, wg=N, rebuild=N, reorder=N (cell order every N rebuilds, "
                 "0: the case's; default every 20 unless that takes over a tenth of the time); same bytes (default: "
                 "vulkan contact,lean; cpu contact)");
  app.add_flag("--quiet", o.quiet, "no progress output");
  app.add_flag("--wall-impulses", o.wall_impulses,
               "wall_forces.csv also gives each wall's largest force and its impulse between frames (the walls' "
               "forces summed every step: one more kernel per step)");
  REPOSE_PARSE(app, argc, argv);
  if (o.backend == "vulkan" && app.count("--threads"))
    return usage_error("--threads applies to the cpu backend (the vulkan backend uses the device)");
  if (o.backend == "cpu" && app.count("--device")) return usage_error("--device applies to the vulkan backend");
  if (steps_opt->count()) o.steps = steps;
  if (time_opt->count()) o.time = sim_time;
  try {
    KernelVariant::parse(o.variant);
  } catch (const std::invalid_argument& e) {
    return usage_error(std::string("--variant: ") + e.what());
  }

  // Everything that can fail on bad input happens before anything is written.
  auto loaded = load_case_or_report(case_path, o.overrides);
  if (!loaded) return 2;
  BackendChoice chosen = resolve_backend(o.backend, o.device);
  o.backend = chosen.backend;
  o.device = chosen.device;
  try {
    return run_case_to_folder(std::move(*loaded), o);
  } catch (const BadInput& e) {  // a folder, a restart state or a step count: nothing was written
    std::fprintf(stderr, "repose run: %s\n", e.what());
    return 2;
  } catch (const MemoryShortfall& e) {
    std::fprintf(stderr, "repose run: %s: %s\n", case_path.c_str(), e.what());
    return 2;
  }
}

}  // namespace

std::vector<Verb> engine_verbs() {
  return {
      {"devices", "list Vulkan devices (lavapipe shows as llvmpipe)", run_devices},
      {"run", "run a case file (VTK frames, summary.json, --state-out)", run_case},
  };
}

}  // namespace repose::cli
