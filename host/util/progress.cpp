#include "util/progress.h"

#include <cstdio>
#include <unistd.h>

namespace repose {

std::string format_duration(double s) {
  char buf[64];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1f s", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  return buf;
}

Progress::Progress(std::string label, uint64_t total_steps, double dt, bool enabled)
    : label_(std::move(label)), total_(total_steps), dt_(dt), enabled_(enabled),
      tty_(::isatty(2)), start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(uint64_t done, const std::string& extra) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  double since = std::chrono::duration<double>(now - last_).count();
  if (since < (tty_ ? 1.0 : 10.0) && done < total_) return;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  double rate = elapsed > 0 ? done / elapsed : 0;
  double eta = rate > 0 ? (total_ - done) / rate : 0;
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
