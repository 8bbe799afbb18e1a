#include "engine/roofline.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <tuple>

#include "engine/cpu_backend.h"
#include "engine/simulation.h"
#include "thread_pool.h"
#include "util/memory_info.h"

namespace repose {

namespace {

constexpr size_t kDramBytes = size_t(256) << 20;  // far larger than any cache

// Median, smallest and largest of some fractions.
struct Spread {
  double median = 0, low = 0, high = 0;
  bool empty = true;
};
Spread spread(std::vector<double> v) {
  Spread s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  size_t m = v.size() / 2;
  s.median = v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  s.low = v.front();
  s.high = v.back();
  s.empty = false;
  return s;
}
std::string text(const Spread& s) {
  if (s.empty) return "-";
  char t[48];
  std::snprintf(t, sizeof t, "%.2f (%.2f-%.2f)", s.median, s.low, s.high);
  return t;
}

// The bytes per step `kernel` moves at the least in a profile (a rebuild's kernels shared over
// its steps), and its seconds per step there; 0 and 0 where it did not run.
std::pair<double, double> per_step(const std::string& kernel, const RunProfile& p, const Layout& layout,
                                   const TrafficCounts& counts) {
  auto t = p.kernels.find(kernel);
  if (t == p.kernels.end() || t->second <= 0 || p.steps == 0) return {0, 0};
  double steps = double(p.steps), dispatches = rebuild_kernel(kernel) ? double(p.rebuilds) : steps;
  return {kernel_min_bytes(kernel, layout, counts) * dispatches / steps, t->second / steps};
}

// contact_forces' milliseconds per step for the law alone and for its bytes at the own copy.
std::pair<double, double> law_and_bytes_ms(const Roofs& r, const Layout& layout, const TrafficCounts& counts) {
  return {1e3 * r.law * counts.contacts, 1e3 * kernel_min_bytes("contact_forces", layout, counts) / r.own};
}

// A kernel's (or several kernels') least bytes and seconds per step, over the run and per segment.
struct Row {
  explicit Row(size_t segments) : segment_bytes(segments, 0), segment_seconds(segments, 0) {}
  double bytes = 0, seconds = 0;
  std::vector<double> segment_bytes, segment_seconds;
  void add(const Row& r) {
    bytes += r.bytes;
    seconds += r.seconds;
    for (size_t k = 0; k < segment_bytes.size(); ++k) {
      segment_bytes[k] += r.segment_bytes[k];
      segment_seconds[k] += r.segment_seconds[k];
    }
  }
};

// `total`: the run's segments added (RooflineRun::total).
Row kernel_row(const std::string& kernel, const RooflineRun& run, const RunProfile& total, const Layout& layout,
               const TrafficCounts& counts) {
  Row r(run.segments.size());
  std::tie(r.bytes, r.seconds) = per_step(kernel, total, layout, counts);
  for (size_t k = 0; k < run.segments.size(); ++k)
    std::tie(r.segment_bytes[k], r.segment_seconds[k]) = per_step(kernel, run.segments[k].profile, layout, counts);
  return r;
}

// One line of the table: milliseconds, bytes and bandwidth per step, and the fractions of the
// two copies over the segments the kernel ran in.
std::string row_text(const std::string& name, const Row& r, const RooflineRun& run) {
  char line[256];
  if (r.bytes == 0) {
    std::snprintf(line, sizeof line, "         %-18s %9.3f %11s\n", name.c_str(), 1e3 * r.seconds, "(no model)");
    return line;
  }
  std::vector<double> of_own, of_dram;
  for (size_t k = 0; k < run.segments.size(); ++k) {
    if (r.segment_seconds[k] <= 0) continue;
    double rate = r.segment_bytes[k] / r.segment_seconds[k];
    of_own.push_back(rate / run.segments[k].roofs.own);
    of_dram.push_back(rate / run.segments[k].roofs.dram);
  }
  std::snprintf(line, sizeof line, "         %-18s %9.3f %11.3g %8.3g %20s %20s\n", name.c_str(), 1e3 * r.seconds,
                r.bytes / 1e6, r.bytes / r.seconds / 1e9, text(spread(of_own)).c_str(), text(spread(of_dram)).c_str());
  return line;
}

}  // namespace

RunProfile RooflineRun::total() const {
  RunProfile p;
  for (const auto& s : segments) p.add(s.profile);
  return p;
}

RooflineRun profile_against_roofs(Simulation& sim, uint32_t steps, int segments) {
  RooflineRun run;
  if (segments <= 0) {
    sim.advance(steps);
    run.segments.push_back({sim.take_profile(), {}});
    return run;
  }
  run.own_bytes = std::min(sim.backend().memory_bytes(), 2 * kDramBytes);
  ThreadPool pool(sim.backend().host_threads());  // the copies split as the kernels are
  CopyMeter dram(kDramBytes, pool);
  std::unique_ptr<CopyMeter> own;
  if (run.own_bytes < 2 * kDramBytes) own = std::make_unique<CopyMeter>(run.own_bytes / 2, pool);
  auto* cpu = dynamic_cast<CpuBackend*>(&sim.backend());
  for (int s = 0; s < segments; ++s) {
    uint64_t begin = uint64_t(steps) * s / segments, end = uint64_t(steps) * (s + 1) / segments;
    sim.advance(end - begin);
    RoofSegment seg{sim.take_profile(), {}};
    seg.roofs.dram = dram.bandwidth();
    seg.roofs.own = own ? own->bandwidth() : seg.roofs.dram;
    seg.roofs.law = cpu ? cpu->contact_law_seconds_per_contact() : 0;
    run.segments.push_back(std::move(seg));
  }
  return run;
}

std::string format_roofline(const RooflineRun& run, const Layout& layout, const TrafficCounts& counts) {
  std::vector<double> own_rates, dram_rates;
  for (const auto& s : run.segments) {
    own_rates.push_back(s.roofs.own / 1e9);
    dram_rates.push_back(s.roofs.dram / 1e9);
  }
  char head[384];
  std::snprintf(head, sizeof head,
                "         memory roofline, after each of %zu segments: a copy moves %s GB/s with the buffers' "
                "footprint (%s), %s GB/s through DRAM (2 x 256 MiB)\n         %-18s %9s %11s %8s %20s %20s\n",
                run.segments.size(), text(spread(own_rates)).c_str(), format_bytes(double(run.own_bytes)).c_str(),
                text(spread(dram_rates)).c_str(), "kernel", "ms/step", "least MB/step", "GB/s", "of own copy",
                "of DRAM copy");
  std::string out = head;
  const RunProfile total = run.total();
  std::vector<std::pair<double, std::string>> sorted;
  for (const auto& [k, t] : total.kernels) sorted.push_back({t, k});
  std::sort(sorted.rbegin(), sorted.rend());
  Row together(run.segments.size());
  for (const auto& [seconds, kernel] : sorted) {
    if (seconds < 0.005 * total.kernel_seconds()) continue;  // under half a percent
    Row r = kernel_row(kernel, run, total, layout, counts);
    out += row_text(kernel, r, run);
    if (r.bytes > 0) together.add(r);
  }
  if (together.seconds > 0) out += row_text("(these together)", together, run);
  return out;
}

std::string format_law_ceiling(const RooflineRun& run, const Layout& layout, const TrafficCounts& counts) {
  std::vector<double> ns, of_law, of_roof;
  for (const auto& s : run.segments) {
    auto [bytes, seconds] = per_step("contact_forces", s.profile, layout, counts);
    if (s.roofs.law <= 0 || seconds <= 0) continue;
    auto [law_ms, bytes_ms] = law_and_bytes_ms(s.roofs, layout, counts);
    ns.push_back(1e9 * s.roofs.law);
    of_law.push_back(law_ms / (1e3 * seconds));
    of_roof.push_back(std::max(law_ms, bytes_ms) / (1e3 * seconds));
  }
  if (ns.empty()) return "";
  Spread law = spread(ns);
  const double median_ms = law.median * 1e-6 * counts.contacts;  // ns per contact to ms per step
  char out[512];
  std::snprintf(out, sizeof out,
                "         compute ceiling: the contact law alone (its rows in registers) %s ns per contact, %.3f ms "
                "per step for %.0f entries (the median)\n         contact_forces, per segment: %s of it; of its "
                "roofline, the larger of it and its bytes at the buffers' copy: %s\n",
                text(law).c_str(), median_ms, counts.contacts,
                text(spread(of_law)).c_str(), text(spread(of_roof)).c_str());
  return out;
}

}  // namespace repose
