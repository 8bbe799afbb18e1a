#include "engine/run_profile.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace repose {

void RunProfile::add(const RunProfile& o) {
  for (const auto& [k, t] : o.kernels) kernels[k] += t;
  wall_seconds += o.wall_seconds;
  steps += o.steps;
  rebuilds += o.rebuilds;
  contact_steps += o.contact_steps;
  reorders += o.reorders;
  reorder_seconds += o.reorder_seconds;
  reorder_parts.download += o.reorder_parts.download;
  reorder_parts.order += o.reorder_parts.order;
  reorder_parts.upload += o.reorder_parts.upload;
  batch_seconds += o.batch_seconds;
  device.add(o.device);
  transfer_seconds += o.transfer_seconds;
}

void RunProfile::add(const ExecuteTimes& batch) {
  for (const auto& [k, t] : batch.kernels) kernels[k] += t;
  device.add(batch.device);
}

double RunProfile::kernel_seconds() const {
  double total = 0;
  for (const auto& [k, t] : kernels) total += t;
  return total;
}

const char* kernel_stage(const std::string& k) {
  if (k == "contact_forces" || k == "contact_rows") return "contacts";
  if (k == "gather_kick" || k == "gather_lean" || k == "kick_drift") return "particles";
  if (k.rfind("body_", 0) == 0) return "bodies";
  if (k == "wall_reduce") return "other";
  return "neighbours";  // rebuild_args, save_old_*, buckets, scans, contact_count/fill, transpose_*
}

// The wall time that neither the kernels nor the reorders took.
static double host_seconds(const RunProfile& p) {
  return std::max(0.0, p.wall_seconds - p.kernel_seconds() - p.reorder_seconds);
}

std::string format_profiles(const std::vector<std::pair<std::string, RunProfile>>& rows, double dt) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-12s %9s %8s %9s %8s %9s %9s   ms per step:", "phase", "steps", "sim s",
                "wall s", "steps/s", "rebuild/k", "contacts");
  out += line;
  for (const char* s : kKernelStages) {
    out += ' ';
    out += s;
  }
  out += " reorder host\n";
  for (const auto& [label, p] : rows) {
    double steps = std::max<double>(1, double(p.steps));
    std::snprintf(line, sizeof line, "%-12s %9llu %8.3g %9.3g %8.4g %9.3g %9.0f                ", label.c_str(),
                  (unsigned long long)p.steps, p.steps * dt, p.wall_seconds,
                  p.wall_seconds > 0 ? p.steps / p.wall_seconds : 0.0, 1000.0 * p.rebuilds / steps,
                  p.contact_steps / steps);
    out += line;
    if (p.kernels.empty()) {
      out += p.steps ? " (kernels not timed)\n" : "\n";
      continue;
    }
    for (const char* s : kKernelStages) {
      double t = 0;
      for (const auto& [k, v] : p.kernels)
        if (std::strcmp(kernel_stage(k), s) == 0) t += v;
      std::snprintf(line, sizeof line, " %*.3f", int(std::strlen(s)), 1e3 * t / steps);
      out += line;
    }
    double host = host_seconds(p);
    std::snprintf(line, sizeof line, " %7.3f %4.3f\n", 1e3 * p.reorder_seconds / steps, 1e3 * host / steps);
    out += line;
  }
  return out;
}

std::string format_kernel_times(const RunProfile& p) {
  std::vector<std::pair<double, std::string>> sorted;
  for (const auto& [k, t] : p.kernels) sorted.push_back({t, k});
  std::sort(sorted.rbegin(), sorted.rend());
  double total = std::max(1e-30, p.kernel_seconds()), steps = std::max<double>(1, double(p.steps));
  std::string out;
  char item[128];
  for (const auto& [t, k] : sorted) {
    if (t / total < 0.005) continue;
    std::snprintf(item, sizeof item, "%s%s %.3f ms (%.0f%%)", out.empty() ? "" : ", ", k.c_str(), 1e3 * t / steps,
                  100 * t / total);
    out += item;
  }
  if (p.reorders) {  // host work, not in the kernels' shares
    const double ms = 1e3 / double(p.reorders);
    std::snprintf(item, sizeof item, "; %llu reorders on the host, %.1f ms each", (unsigned long long)p.reorders,
                  ms * p.reorder_seconds);
    out += item;
    const RunProfile::ReorderParts& r = p.reorder_parts;
    if (r.download + r.order + r.upload > 0) {  // absent from a checkpoint's profile of before they were timed
      std::snprintf(item, sizeof item, " (the state down %.1f, into its new slots %.1f, up %.1f)", ms * r.download,
                    ms * r.order, ms * r.upload);
      out += item;
    }
  }
  return out;
}

std::string format_host_times(const RunProfile& p) {
  if (p.kernels.empty() || p.steps == 0) return "";
  const double ms = 1e3 / double(p.steps);
  const double beyond = std::max(0.0, p.batch_seconds - p.kernel_seconds());
  const double rest = std::max(0.0, host_seconds(p) - beyond - p.transfer_seconds);
  auto per_step = [ms](const char* name, double seconds) {
    char number[32];
    std::snprintf(number, sizeof number, " %.3f", seconds * ms);
    return name + std::string(number);
  };
  std::string out = per_step("host", host_seconds(p)) + " ms per step: " +
                    per_step("running the batches besides their kernels", beyond);
  const DeviceOverheads& d = p.device;
  if (d.total() > 0) {  // a device's batches; what is left of them is the submit and the wait
    out += " (";
    if (d.pipelines > 0) out += per_step("creating pipelines", d.pipelines) + ", ";  // a one-off
    out += per_step("recording the commands", d.recording) + ", " +
           per_step("the device between kernels", d.between_kernels) + ", " +
           per_step("submitting and waiting", std::max(0.0, beyond - d.total())) + ")";
  }
  return out + ", " + per_step("transfers", p.transfer_seconds) + ", " + per_step("between batches", rest);
}

}  // namespace repose
