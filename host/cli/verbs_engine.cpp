// `repose devices`, `repose run`, `repose bench`: the engine's verbs.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/cli_case.h"
#include "cli/cli_checks.h"
#include "cli/verbs.h"
#include "engine/backend_factory.h"
#include "engine/bench_bed.h"
#include "engine/model.h"
#include "engine/simulation.h"
#include "io/case_run.h"
#include "io/output_dir.h"
#include "io/state_file.h"
#include "util/progress.h"
#include "vk/context.h"

namespace repose::cli {

namespace {

namespace fs = std::filesystem;

// "--variant rows,lean,wg=128,rebuild=20" -> KernelVariant; throws on anything else.
KernelVariant parse_variant(const std::string& text) { return KernelVariant::parse(text); }

int run_devices(int argc, char** argv) {
  CLI::App app{"List the Vulkan devices and which one `repose run` uses."};
  CLI11_PARSE(app, argc, argv);
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
  std::printf("* = used by default (--device N chooses another)\n");
  return 0;
}

int run_case(int argc, char** argv) {
  CLI::App app{"Run a case file: progress on stderr; VTK frames, wall forces and summary.json in --out."};
  std::string case_path;
  CaseRunOptions o;
  uint64_t steps = 0;
  double sim_time = 0;
  app.add_option("case", case_path, "case file (TOML)")->required();
  app.add_option("--backend", o.backend, "vulkan (default) or cpu")->check(CLI::IsMember({"vulkan", "cpu"}));
  app.add_option("--device", o.device, "Vulkan device index (see `repose devices`)")->check(whole_number(0, 63));
  app.add_option("--threads", o.threads, "cpu backend threads (default: all cores)")->check(thread_count());
  auto* steps_opt = app.add_option("--steps", steps, "run this many steps instead of the case's end time (with --restart: this many more)")
                        ->check(whole_number(0, 1000000000000LL));
  auto* time_opt = app.add_option("--time", sim_time, "run this much simulated time, s (with --restart: this much more)")
                       ->excludes(steps_opt)->check(finite_positive());
  app.add_option("--out", o.out_dir, "output folder, new or empty (default out/CASE_NAME)");
  app.add_flag("--overwrite", o.overwrite, "delete what --out holds before the run");
  app.add_option("--state-out", o.state_out, "write the final state here (docs/state-format.md)");
  app.add_option("--restart", o.restart,
                 "continue from a state file (--state-out or a checkpoint): same bytes as a run that never stopped");
  app.add_option("--set", o.overrides, "override a case key: KEY=VALUE (repeatable)");
  app.add_option("--variant", o.variant,
                 "kernel variant: contact|rows, lean|full, wg=N, rebuild=N (default: vulkan contact,lean; cpu contact)");
  app.add_flag("--quiet", o.quiet, "no progress output");
  CLI11_PARSE(app, argc, argv);
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
  try {
    return run_case_to_folder(*loaded, o);
  } catch (const OutputError& e) {
    std::fprintf(stderr, "repose run: %s\n", e.what());
    return 2;
  }
}

int run_bench(int argc, char** argv) {
  CLI::App app{"Benchmark a settled bed of 10 mm spheres on each backend and kernel variant."};
  uint32_t n = 50000;
  std::vector<std::string> backends{"cpu", "vulkan"};
  std::vector<std::string> variants{"contact"};
  unsigned threads = 0;
  int device = -1;
  uint32_t steps = 200;
  double settle = 0.6;
  std::string cache_dir = "out/bench";
  app.add_option("--n", n, "spheres in the bed (default 50000)");
  app.add_option("--backend", backends, "cpu and/or vulkan (default both)");
  app.add_option("--threads", threads, "cpu backend threads (default all cores)");
  app.add_option("--device", device, "Vulkan device index");
  app.add_option("--variant", variants, "kernel variants to compare, e.g. contact rows,wg=128");
  app.add_option("--steps", steps, "timed steps per backend and variant (default 200)");
  app.add_option("--settle", settle, "simulated seconds to settle a new bed (default 0.6)");
  app.add_option("--cache", cache_dir, "folder for the settled bed (reused when present)");
  std::string case_path;
  app.add_option("--case", case_path,
                 "benchmark this case instead of the bed, after --settle simulated seconds of it");
  CLI11_PARSE(app, argc, argv);

  bool own_case = !case_path.empty();
  CaseSpec bed;
  if (own_case) {
    auto loaded = load_case_or_report(case_path, {});
    if (!loaded) return 2;
    bed = *loaded;
  } else {
    bed = bench_bed_case(n);
  }
  Model model = build_model(bed);
  n = model.n_particles;
  fs::create_directories(cache_dir);
  std::string cache = cache_dir + "/" + (own_case ? fs::path(case_path).stem().string() : "bed") + "_" +
                      std::to_string(n) + (own_case ? "_" + std::to_string(settle) : "") + ".state";
  if (fs::exists(cache)) {
    HostState s = read_state_file(cache);
    model.pos = s.pos;
    model.vel = s.vel;
    model.omega = s.omega;
    if (!s.bodies.empty()) model.bodies = s.bodies;
    std::fprintf(stderr, "bench: settled state of %u particles from %s\n", n, cache.c_str());
  } else {
    std::fprintf(stderr, "bench: settling %u spheres for %.2f s (once; cached in %s)\n", n, settle, cache.c_str());
    Simulation s(model, make_backend("cpu", -1, threads, gpu::kDefaultWorkgroup));
    uint64_t settle_steps = uint64_t(std::llround(settle / model.dt));
    Progress p("settle", settle_steps, model.dt);
    s.advance(settle_steps, [&](const Simulation& x) { p.update(x.step()); });
    p.finish();
    write_state_file(cache, s.state(), s.step(), s.time());
    model.pos = s.state().pos;
    model.vel = s.state().vel;
    model.omega = s.state().omega;
    if (!s.state().bodies.empty()) model.bodies = s.state().bodies;
  }

  if (own_case)
    std::printf("%s after %.3g s: %u particles, %zu bodies, dt = %.3g s, %u timed steps\n",
                case_path.c_str(), settle, n, model.bodies.size(), model.dt, steps);
  else
    std::printf("settled bed: %u spheres of 10 mm, dt = %.3g s (0.2 Rayleigh), %u timed steps\n",
                n, model.dt, steps);
  std::printf("%-8s %-20s %14s %14s %10s %10s %10s %9s\n", "backend", "variant", "particle-st/s",
              "contacts/s", "contacts", "B/particle", "B/contact", "rebuilds");
  for (const auto& b : backends) {
    for (const auto& vt : variants) {
      KernelVariant v = parse_variant(vt);
      Simulation sim(model, make_backend(b, device, threads, v.workgroup), v, 50);
      sim.advance(50);  // warm up: list built, caches hot
      uint32_t rebuilds_before = sim.rebuilds();
      auto t0 = std::chrono::steady_clock::now();
      sim.advance(steps);
      double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      uint32_t rebuilds = sim.rebuilds() - rebuilds_before;
      double contacts = sim.contacts();
      // Memory split: buffers sized by particles (and hash buckets) vs by list capacity.
      Layout probe;
      probe.lean_contacts = v.lean;
      probe.rolling_springs = (model.flags & gpu::kFlagRollingSpring) != 0;
      size_t per_contact_bytes = bytes_per_contact(probe);
      double bytes_per_particle =
          double(sim.backend().memory_bytes() - size_t(sim.capacity()) * per_contact_bytes) / n;
      std::printf("%-8s %-20s %14.4g %14.4g %10.0f %10.0f %10zu %9u\n", b.c_str(), v.name().c_str(),
                  double(n) * steps / secs, contacts * steps / secs, contacts, bytes_per_particle,
                  per_contact_bytes, rebuilds);
      auto times = sim.time_kernels(10);
      double total = 0;
      for (const auto& [k, t] : times) total += t;
      std::printf("         time per step by kernel (%s):", sim.backend().describe().c_str());
      for (const auto& [k, t] : times)
        if (t / total > 0.01) std::printf(" %s %.2f ms,", k.c_str(), 1e3 * t / 10);
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

std::vector<Verb> engine_verbs() {
  return {
      {"devices", "list Vulkan devices (lavapipe shows as llvmpipe)", run_devices},
      {"run", "run a case file (VTK frames, summary.json, --state-out)", run_case},
      {"bench", "speed of a settled bed per backend and kernel variant", run_bench},
  };
}

}  // namespace repose::cli
