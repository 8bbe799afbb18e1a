// `repose devices`, `repose run`, `repose bench`: the engine's verbs.
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
#include "engine/buffer_table.h"
#include "engine/bench_bed.h"
#include "contact_lanes.h"
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
                 "kernel variant: contact|rows, lean|full, wg=N, rebuild=N (default: vulkan contact,lean; cpu contact)");
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
    return run_case_to_folder(*loaded, o);
  } catch (const BadInput& e) {  // a folder, a restart state or a step count: nothing was written
    std::fprintf(stderr, "repose run: %s\n", e.what());
    return 2;
  }
}

// The bed or case to benchmark, settled for `settle` simulated seconds on the default backend
// (a hardware GPU when there is one: every backend gives the same bytes) once
// and cached in `cache_dir` (the file name carries the size, the settling time and the skin).
Model settled_bench_model(CaseSpec spec, bool own_case, double settle, double skin, unsigned threads,
                          const std::string& cache_dir, double& energy) {
  if (skin >= 0) spec.neighbour.skin = skin;
  Model model = build_model(spec);
  uint32_t n = model.n_particles;
  fs::create_directories(cache_dir);
  char tail[64];
  std::snprintf(tail, sizeof tail, "_%u_%gs.state", n, settle);
  std::string cache = cache_dir + "/" + (own_case ? fs::path(spec.path).stem().string() : "bed") + tail;
  HostState s;
  if (fs::exists(cache)) {
    s = read_state_file(cache);
    std::fprintf(stderr, "bench: settled state of %u particles from %s\n", n, cache.c_str());
  } else {
    std::fprintf(stderr, "bench: settling %u particles for %.2f s (once; cached in %s)\n", n, settle, cache.c_str());
    Simulation sim(model, make_backend("auto", -1, threads, gpu::kDefaultWorkgroup));
    uint64_t settle_steps = uint64_t(std::llround(settle / model.dt));
    Progress p("settle", settle_steps, model.dt);
    sim.advance(settle_steps, [&](const Simulation& x) { p.update(x.step()); });
    p.finish();
    write_state_file(cache, sim.state(), sim.step(), sim.time());
    s = sim.state();
  }
  model.pos = s.pos;
  model.vel = s.vel;
  model.omega = s.omega;
  if (!s.bodies.empty()) model.bodies = s.bodies;
  energy = kinetic_energy(s).total();
  return model;
}

// Touching entries of the list (a contact's age counts the steps it has touched).
size_t touching_contacts(const HostState& s) {
  size_t k = 0;
  for (const auto& h : s.history) k += h.w > 0;
  return k;
}

// One backend and variant on the settled model: speed, list size and memory, then where the
// time goes (every kernel timed over the same number of steps).
void bench_one(const Model& model, const std::string& backend, const KernelVariant& v, int device, unsigned threads,
               uint32_t steps) {
  Simulation sim(model, make_backend(backend, device, threads, v.workgroup), v, 50);
  sim.advance(50);  // warm up: list built, caches hot
  uint32_t rebuilds_before = sim.rebuilds();
  auto t0 = std::chrono::steady_clock::now();
  std::clock_t c0 = std::clock();
  sim.advance(steps);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double cpu_secs = double(std::clock() - c0) / CLOCKS_PER_SEC;
  uint32_t rebuilds = sim.rebuilds() - rebuilds_before;
  double contacts = sim.contacts(), n = model.n_particles;
  // Memory split: buffers sized by particles (and hash buckets) vs by list capacity.
  Layout probe;
  probe.lean_contacts = v.lean;
  probe.rolling_springs = (model.flags & gpu::kFlagRollingSpring) != 0;
  size_t per_contact_bytes = bytes_per_contact(probe);
  double bytes_per_particle = double(sim.backend().memory_bytes() - size_t(sim.capacity()) * per_contact_bytes) / n;
  std::printf("%-8s %-20s %14.4g %14.4g %10.0f %9zu %10.0f %10zu %9.3g %8.3g\n", backend.c_str(), v.name().c_str(),
              n * steps / secs, contacts * steps / secs, contacts, touching_contacts(sim.state()),
              bytes_per_particle, per_contact_bytes, 1000.0 * rebuilds / steps, cpu_secs);
  sim.set_profiling(true);
  sim.take_profile();
  sim.advance(steps);
  RunProfile p = sim.take_profile();
  std::printf("         %s, every kernel timed:\n%s         per step: %s\n", sim.backend().describe().c_str(),
              format_profiles({{"timed", p}}, model.dt).c_str(), format_kernel_times(p).c_str());
  std::fflush(stdout);
}

int run_bench(int argc, char** argv) {
  CLI::App app{"Benchmark a settled bed of 10 mm spheres on each backend and kernel variant."};
  uint32_t n = 50000;
  std::vector<std::string> backends{"cpu", "vulkan"};
  std::vector<std::string> variants;
  unsigned threads = 0;
  int device = -1;
  uint32_t steps = 200;
  double settle = 0.6, skin = -1;
  std::string cache_dir = "out/bench", case_path;
  bool scalar_contacts = false;
  app.add_option("--n", n, "spheres in the bed (default 50000)");
  app.add_option("--backend", backends, "cpu and/or vulkan (default both)");
  app.add_option("--threads", threads, "cpu backend threads (default all cores)");
  app.add_option("--device", device, "Vulkan device index");
  app.add_option("--variant", variants,
                 "kernel variants to compare, e.g. contact rows,wg=128 (default: what `repose run` uses on each backend)");
  app.add_option("--steps", steps, "timed steps per backend and variant (default 200)");
  app.add_option("--settle", settle, "simulated seconds to settle a new bed (default 0.6)");
  app.add_option("--skin", skin, "neighbour skin (m; default the case's): results do not depend on it");
  app.add_option("--cache", cache_dir, "folder for the settled bed (reused when present)")
      ->check(non_empty_path());
  app.add_option("--case", case_path, "benchmark this case instead of the bed, after --settle simulated seconds of it");
  app.add_flag("--scalar-contacts", scalar_contacts,
               "cpu backend: the contact kernel one contact at a time, not in SIMD lanes (same bytes)");
  REPOSE_PARSE(app, argc, argv);
  if (scalar_contacts) gpu::set_contact_lanes(false);
  std::vector<KernelVariant> named;  // checked before a bed is settled
  try {
    for (const auto& vt : variants) named.push_back(KernelVariant::parse(vt));
  } catch (const std::invalid_argument& e) {
    return usage_error(std::string("--variant: ") + e.what());
  }

  bool own_case = !case_path.empty();
  CaseSpec spec;
  if (own_case) {
    auto loaded = load_case_or_report(case_path, {});
    if (!loaded) return 2;
    spec = *loaded;
  } else {
    spec = bench_bed_case(n);
  }
  double energy = 0;
  Model model = settled_bench_model(spec, own_case, settle, skin, threads, cache_dir, energy);
  n = model.n_particles;
  if (own_case)
    std::printf("%s after %.3g s: %u particles, %zu bodies, dt = %.3g s, skin %.3g mm, kinetic energy %.3g J, %u timed steps\n",
                case_path.c_str(), settle, n, model.bodies.size(), model.dt, 1e3 * model.skin, energy, steps);
  else
    std::printf("bed settled for %.3g s: %u spheres of 10 mm, dt = %.3g s (0.2 Rayleigh), skin %.3g mm, kinetic energy %.3g J, %u timed steps\n",
                settle, n, model.dt, 1e3 * model.skin, energy, steps);
  // cpu s: processor time of the timed steps (all threads; lavapipe's threads included), the
  // figure to compare on a shared machine. rebuild/k: list rebuilds per 1000 steps, as in the
  // per-kernel table below (which times another run of as many steps).
  std::printf("%-8s %-20s %14s %14s %10s %9s %10s %10s %9s %8s\n", "backend", "variant", "particle-st/s", "contacts/s",
              "contacts", "touching", "B/particle", "B/contact", "rebuild/k", "cpu s");
  for (const auto& b : backends) {
    if (named.empty()) bench_one(model, b, KernelVariant::fastest_for(b, model), device, threads, steps);
    for (const auto& v : named) bench_one(model, b, v, device, threads, steps);
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
