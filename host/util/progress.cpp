#include "util/progress.h"

#include <algorithm>
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
    : label_(std::move(label)), limit_(total_steps), dt_(dt), enabled_(enabled),
      tty_(::isatty(2)), start_(std::chrono::steady_clock::now()), last_(start_), first_(first_step) {}

void Progress::expect_end_time(double seconds, const std::string& why) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return expect_unknown_end(why);
  expected_end_ = std::min(seconds / dt_, double(limit_));
  why_ = why;
}

void Progress::expect_unknown_end(const std::string& why) {
  expected_end_ = -2;
  why_ = why;
}

std::string Progress::line(uint64_t done, double elapsed, const std::string& extra) const {
  double rate = elapsed > 0 && done > first_ ? double(done - first_) / elapsed : 0;
  double end = expected_end_ == -1 ? double(limit_) : expected_end_;
  bool known = end >= 0;
  // A run may go past its expectation (it is revised at the next sample): the end is then now.
  if (known) end = std::max(end, double(done));
  char head[512];
  if (known)
    std::snprintf(head, sizeof head, "%s: t = %.4g s of %.4g s%s%s, step %llu/%.0f, %.0f steps/s, ETA %s",
                  label_.c_str(), double(done) * dt_, end * dt_, why_.empty() ? "" : " ", why_.c_str(),
                  (unsigned long long)done, end, rate, format_duration(rate > 0 ? (end - double(done)) / rate : -1).c_str());
  else
    std::snprintf(head, sizeof head, "%s: t = %.4g s (at most %.4g s), step %llu, %.0f steps/s, ETA unknown%s%s",
                  label_.c_str(), double(done) * dt_, double(limit_) * dt_, (unsigned long long)done, rate,
                  why_.empty() ? "" : " ", why_.c_str());
  return std::string(head) + (extra.empty() ? "" : ", " + extra);
}

void Progress::update(uint64_t done, const std::string& extra) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  double since = std::chrono::duration<double>(now - last_).count();
  double wait = tty_ ? 1.0 : printed_ ? 10.0 : 2.0;
  if (since < wait) return;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "%s%s%s", tty_ ? "\r" : "", line(done, elapsed, extra).c_str(), tty_ ? "   " : "\n");
  std::fflush(stderr);
  last_ = now;
  printed_ = true;
}

void Progress::finish() {
  if (enabled_ && tty_ && printed_) std::fprintf(stderr, "\n");
}

TaskProgress::TaskProgress(std::string label, int total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

void TaskProgress::next(const std::string& what) {
  ++done_;
  if (!enabled_) return;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  double eta = done_ > 1 ? elapsed / (done_ - 1) * (total_ - done_ + 1) : -1;
  std::fprintf(stderr, "%s %d/%d %s, %s elapsed, ETA %s\n", label_.c_str(), done_, total_, what.c_str(),
               format_duration(elapsed).c_str(), format_duration(eta).c_str());
  std::fflush(stderr);
}

void FallingTrend::add(double t, double value) {
  if (log_ && !(value > 0)) return;
  t_.push_back(t);
  v_.push_back(log_ ? std::log(value) : value);
  size_t old = 0;
  while (old < t_.size() && t_[old] < t - window_) ++old;
  t_.erase(t_.begin(), t_.begin() + long(old));
  v_.erase(v_.begin(), v_.begin() + long(old));
}

double FallingTrend::reaches(double target) const {
  if (t_.size() < 3 || (log_ && !(target > 0))) return -1;
  double n = double(t_.size()), mt = 0, mv = 0;
  for (size_t k = 0; k < t_.size(); ++k) mt += t_[k] / n, mv += v_[k] / n;
  double stt = 0, stv = 0;
  for (size_t k = 0; k < t_.size(); ++k) stt += (t_[k] - mt) * (t_[k] - mt), stv += (t_[k] - mt) * (v_[k] - mv);
  double slope = stt > 0 ? stv / stt : 0;
  if (!(slope < 0)) return -1;
  double goal = log_ ? std::log(target) : target;
  double last = v_.back();  // from the latest value, along the fitted slope
  return goal >= last ? t_.back() : t_.back() + (goal - last) / slope;
}

}  // namespace repose
