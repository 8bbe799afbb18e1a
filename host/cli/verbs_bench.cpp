// `repose bench`: a settled bed (or a case) per backend and kernel variant: speed, the time and
// memory of setting it up, and each kernel's share of the machine's memory bandwidth.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "cli/cli_case.h"
#include "cli/cli_checks.h"
#include "cli/verbs.h"
#include "lane_switches.h"
#include "engine/backend_factory.h"
#include "engine/bench_bed.h"
#include "engine/buffer_table.h"
#include "engine/cpu_backend.h"
#include "engine/kernel_traffic.h"
#include "engine/memory_need.h"
#include "engine/model.h"
#include "engine/roofline.h"
#include "engine/wall_grid.h"
#include "engine/simulation.h"
#include "io/state_file.h"
#include "util/memory_info.h"
#include "util/progress.h"

namespace repose::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Wall and processor seconds of a part of the setup (the processor's is the figure to compare on
// a shared machine).
struct Stopwatch {
  Clock::time_point wall = Clock::now();
  std::clock_t cpu = std::clock();
  std::string text() const {
    char t[64];
    std::snprintf(t, sizeof t, "%.3g s (%.3g cpu s)", seconds_since(wall), double(std::clock() - cpu) / CLOCKS_PER_SEC);
    return t;
  }
};

// The model after `settle` simulated seconds on the default backend (a hardware GPU when there is
// one: every backend gives the same bytes), run once and cached in
// `cache` (a state file); with settle 0 the model as the case starts, nothing cached.
Model settled_bench_model(Model model, double settle, unsigned threads, const std::string& cache, double& energy) {
  HostState s;
  if (settle <= 0) {
    s.vel = model.vel;
    s.omega = model.omega;
    s.bodies = model.bodies;
    energy = kinetic_energy(s).total();
    return model;
  }
  uint32_t n = model.n_particles;
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

// The timed steps run in this many segments on the cpu backend, each followed by its roofs.
constexpr int kRoofSegments = 8;

// One backend and variant on the settled model: setup, speed, list size and memory, then where
// the time goes (every kernel timed over the same number of steps) and how close to the
// memory bandwidth it runs.
void bench_one(const Model& model, const std::string& backend, const KernelVariant& v, int device, unsigned threads,
               uint32_t steps) {
  MemoryNeed need = check_run_memory(model, v, 50, backend, device, false);
  Stopwatch setup;
  Simulation sim(model, make_backend(backend, device, threads, v.workgroup), v, 50);
  std::string setup_time = setup.text();
  size_t resident_after_setup = resident_bytes(), peak_after_setup = peak_resident_bytes();
  sim.advance(50);  // warm up: list built, caches hot
  uint32_t rebuilds_before = sim.rebuilds();
  auto t0 = Clock::now();
  std::clock_t c0 = std::clock();
  sim.advance(steps);
  double secs = seconds_since(t0);
  double cpu_secs = double(std::clock() - c0) / CLOCKS_PER_SEC;
  uint32_t rebuilds = sim.rebuilds() - rebuilds_before;
  double contacts = sim.contacts(), n = model.n_particles;
  size_t per_contact_bytes = bytes_per_contact(sim.layout());
  double bytes_per_particle = double(sim.backend().memory_bytes() - size_t(sim.capacity()) * per_contact_bytes) / n;
  std::printf("%-8s %-20s %14.4g %14.4g %10.0f %9zu %10.0f %10zu %9.3g %8.3g\n", backend.c_str(), v.name().c_str(),
              n * steps / secs, contacts * steps / secs, contacts, touching_contacts(sim.state()),
              bytes_per_particle, per_contact_bytes, 1000.0 * rebuilds / steps, cpu_secs);
  size_t stepping = resident_bytes();
  std::printf("         setup %s (buffers, first neighbour list and forces); memory: %s; this process: %s "
              "resident after setup (peak %s), %s while stepping (%.0f B per particle)\n",
              setup_time.c_str(), describe_memory_need(need).c_str(), format_bytes(double(resident_after_setup)).c_str(),
              format_bytes(double(peak_after_setup)).c_str(), format_bytes(double(stepping)).c_str(),
              double(stepping) / n);
  sim.set_profiling(true);
  sim.take_profile();
  const bool cpu = backend == "cpu";  // the roofs are the host's
  RooflineRun run = profile_against_roofs(sim, steps, cpu ? kRoofSegments : 0);
  RunProfile p = run.total();
  std::printf("         %s, every kernel timed:\n%s         per step: %s\n         %s\n", sim.backend().describe().c_str(),
              format_profiles({{"timed", p}}, model.dt).c_str(), format_kernel_times(p).c_str(),
              format_host_times(p).c_str());
  if (cpu) {
    TrafficCounts counts{n, double(sim.contacts()), double(sim.contacts()), double(model.table_size) + 2};
    std::printf("%s%s", format_roofline(run, sim.layout(), counts).c_str(),
                format_law_ceiling(run, sim.layout(), counts).c_str());
  }
  std::fflush(stdout);
}

// What is benchmarked (the case or the bed, settled), how long its setup took, and the header of
// the table bench_one's rows fill; an empty case_path is the bed.
void print_bench_subject(const std::string& case_path, const Model& model, double settle, double energy,
                         uint32_t steps, const std::string& case_seconds, const std::string& model_seconds) {
  bool own_case = !case_path.empty();
  uint32_t n = model.n_particles;
  if (own_case)
    std::printf("%s after %.3g s: %u particles, %zu bodies, dt = %.3g s, skin %.3g mm, kinetic energy %.3g J, %u timed steps\n",
                case_path.c_str(), settle, n, model.bodies.size(), model.dt, 1e3 * model.skin, energy, steps);
  else
    std::printf("bed settled for %.3g s: %u spheres of 10 mm, dt = %.3g s (0.2 Rayleigh), skin %.3g mm, kinetic energy %.3g J, %u timed steps\n",
                settle, n, model.dt, 1e3 * model.skin, energy, steps);
  std::printf("setup: case %s (%s), model %s\n", case_seconds.c_str(),
              own_case ? "read, fills placed" : "the bed's spheres on a jittered lattice", model_seconds.c_str());
  if (!model.walls.empty()) std::printf("walls: %s\n", describe_wall_grid(model).c_str());
  // cpu s: processor time of the timed steps (all threads; lavapipe's threads included), the
  // figure to compare on a shared machine.
  std::printf("%-8s %-20s %14s %14s %10s %9s %10s %10s %9s %8s\n", "backend", "variant", "particle-st/s", "contacts/s",
              "contacts", "touching", "B/particle", "B/contact", "rebuild/k", "cpu s");
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
  bool scalar_contacts = false, scalar_kick = false, scalar_bodies = false, scalar_neighbours = false;
  app.add_option("--n", n, "spheres in the bed (default 50000)");
  app.add_option("--backend", backends, "cpu and/or vulkan (default both)");
  app.add_option("--threads", threads, "cpu backend threads (default all cores)");
  app.add_option("--device", device, "Vulkan device index");
  app.add_option("--variant", variants,
                 "kernel variants to compare, e.g. contact rows,wg=128 (default: what `repose run` uses on each backend)");
  app.add_option("--steps", steps, "timed steps per backend and variant (default 200)");
  app.add_option("--settle", settle, "simulated seconds to settle a new bed (default 0.6; 0: time the setup of "
                                     "the bed or case as it starts, nothing cached)");
  app.add_option("--skin", skin, "neighbour skin (m; default the case's): results do not depend on it");
  app.add_option("--cache", cache_dir, "folder for the settled bed (reused when present)");
  app.add_option("--case", case_path, "benchmark this case instead of the bed, after --settle simulated seconds of it");
  std::vector<std::string> sets;
  app.add_option("--set", sets, "with --case: override a case key, KEY=VALUE (repeatable)");
  app.add_flag("--scalar-contacts", scalar_contacts,
               "cpu backend: the contact kernel one contact at a time, not in SIMD lanes (same bytes)");
  app.add_flag("--scalar-kick", scalar_kick,
               "cpu backend: kick_drift and gather_kick's kick one particle at a time, not in SIMD lanes (same bytes)");
  app.add_flag("--scalar-bodies", scalar_bodies,
               "cpu backend: body_place and body_gather_kick one sub-sphere or body at a time, not in SIMD lanes "
               "(same bytes)");
  app.add_flag("--scalar-neighbours", scalar_neighbours,
               "cpu backend: the neighbour list as the shaders build it, the walk one slot at a time and the transposed "
               "rows by atomic cursor, then sorted (same bytes)");
  CLI11_PARSE(app, argc, argv);
  if (scalar_contacts) gpu::set_lanes(gpu::LaneKernels::Contacts, false);
  if (scalar_kick) gpu::set_lanes(gpu::LaneKernels::Kick, false);
  if (scalar_bodies) gpu::set_lanes(gpu::LaneKernels::Bodies, false);
  if (scalar_neighbours) gpu::set_lanes(gpu::LaneKernels::Neighbours, false);
  std::vector<KernelVariant> named;  // checked before a bed is settled
  try {
    for (const auto& vt : variants) named.push_back(KernelVariant::parse(vt));
  } catch (const std::invalid_argument& e) {
    return usage_error(std::string("--variant: ") + e.what());
  }

  // Setup, timed: the case (a fill places its particles here), then the model.
  bool own_case = !case_path.empty();
  Stopwatch case_time;
  CaseSpec spec;
  if (own_case) {
    auto loaded = load_case_or_report(case_path, sets);
    if (!loaded) return 2;
    spec = std::move(*loaded);
  } else {
    spec = bench_bed_case(n);
  }
  std::string case_seconds = case_time.text();
  if (skin >= 0) spec.neighbour.skin = skin;
  Stopwatch model_time;
  Model model = build_model(spec);
  std::string model_seconds = model_time.text();
  std::vector<SphereSpec>().swap(spec.spheres);  // the model holds the particles now
  std::vector<BodySpec>().swap(spec.bodies);
  n = model.n_particles;
  char tail[64];
  std::snprintf(tail, sizeof tail, "_%u_%gs.state", n, settle);
  std::string cache = cache_dir + "/" + (own_case ? fs::path(spec.path).stem().string() : "bed") + tail;
  if (settle > 0) fs::create_directories(cache_dir);
  double energy = 0;
  model = settled_bench_model(std::move(model), settle, threads, cache, energy);
  print_bench_subject(case_path, model, settle, energy, steps, case_seconds, model_seconds);
  try {
    for (const auto& b : backends) {
      if (named.empty()) bench_one(model, b, KernelVariant::fastest_for(b, model), device, threads, steps);
      for (const auto& v : named) bench_one(model, b, v, device, threads, steps);
    }
  } catch (const MemoryShortfall& e) {
    std::fprintf(stderr, "repose bench: %s\n", e.what());
    return 2;
  }
  return 0;
}

}  // namespace

std::vector<Verb> bench_verbs() {
  return {{"bench", "speed, setup, memory and memory-bandwidth roofline of a settled bed per backend and variant",
           run_bench}};
}

}  // namespace repose::cli
