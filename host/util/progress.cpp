#include "util/progress.h"

#include <cmath>
#include <cstdio>
#include <unistd.h>

namespace repose {

std::string format_duration(double s) {
  char buf[64];
  if (!(s >= 0)) return "unknown";
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1f s", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s / 60), int(std::fmod(s, 60)));
  else if (s < 86400) std::snprintf(buf, sizeof buf, "%dh%02dm", int(s / 3600), int(std::fmod(s, 3600) / 60));
  else if (s < 100 * 365.25 * 86400) std::snprintf(buf, sizeof buf, "%.0fd%02dh", std::floor(s / 86400), int(std::fmod(s, 86400) / 3600));
  else return "more than 100 years";
  return buf;
}

Progress::Progress(std::string label, uint64_t total_steps, double dt, bool enabled, uint64_t first_step)
    : label_(std::move(label)), total_(total_steps), dt_(dt), enabled_(enabled),
      tty_(::isatty(2)), start_(std::chrono::steady_clock::now()), last_(start_), first_(first_step) {}

void Progress::update(uint64_t done, const std::string& extra) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  double since = std::chrono::duration<double>(now - last_).count();
  if (since < (tty_ ? 1.0 : 10.0) && done < total_) return;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  double rate = elapsed > 0 && done > first_ ? double(done - first_) / elapsed : 0;
  double eta = rate > 0 ? double(total_ - done) / rate : -1;
  std::fprintf(stderr, "%s%s: t = %.4g s of %.4g s, step %llu/%llu, %.0f steps/s, ETA %s%s%s",
               tty_ ? "\r" : "", label_.c_str(), done * dt_, total_ * dt_,
               (unsigned long long)done, (unsigned long long)total_, rate,
               format_duration(eta).c_str(), extra.empty() ? "" : ", ", extra.c_str());
  std::fprintf(stderr, tty_ ? "   " : "\n");
  std::fflush(stderr);
  last_ = now;
  last_steps_ = done;
}

void Progress::finish() {
  if (enabled_ && tty_) std::fprintf(stderr, "\n");
}

}  // namespace repose
