#include "calibrate/executor.h"

#include <algorithm>
#include <mpi.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "calibrate/run_job.h"
#include "util/progress.h"

namespace repose::calibrate {

namespace {

std::string describe(const RunRecord& r, const CampaignPlan& plan) {
  std::string s;
  char buf[64];
  for (size_t i = 0; i < plan.factors.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%s=%.5g", i ? " " : "", plan.factors[i].name.c_str(), r.spec.x[i]);
    s += buf;
  }
  const char* arrow = " ->";
  for (const auto& response : plan.responses) {
    auto it = r.responses.find(response.name);
    if (response.rig != r.spec.rig || it == r.responses.end()) continue;
    std::snprintf(buf, sizeof buf, "%s %s=%.6g", arrow, response.name.c_str(), it->second);
    s += buf;
    arrow = ",";
  }
  return s;
}

}  // namespace

Executor::Executor(const CampaignPlan& plan, RunStore& store, MpiSession& mpi, int jobs, bool quiet, unsigned threads)
    : plan_(plan), store_(store), mpi_(mpi), jobs_(jobs), quiet_(quiet), threads_(std::max(1u, threads)) {
  if (jobs_ < 1 && !mpi_.has_workers()) jobs_ = 1;
}

// What the local worker threads and the coordinating loop share: the next job to hand out, the
// local outcomes not yet stored, the first error. `received` and `start` belong to the
// coordinating thread.
struct Executor::Batch {
  Batch(const std::vector<RunJob>& jobs, const std::string& name) : pending(jobs), label(name) {}
  const std::vector<RunJob>& pending;
  const std::string& label;
  std::mutex mutex;
  std::condition_variable wake;
  size_t next = 0;  // jobs handed out
  bool failed = false;
  std::deque<JobOutcome> finished;
  std::string first_error;
  size_t received = 0;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

  // The next job, unless a run failed (then no more are handed out).
  const RunJob* take() {
    std::lock_guard lock(mutex);
    return (!failed && next < pending.size()) ? &pending[next++] : nullptr;
  }
  void fail(const std::string& error) {
    std::lock_guard lock(mutex);
    if (!failed) first_error = error;
    failed = true;
  }
  // A local worker thread: runs jobs until none is left to take.
  void work(int rank) {
    while (const RunJob* job = take()) {
      JobOutcome out;
      try {
        out = execute_job(*job, rank);
      } catch (const std::exception& e) {  // execute_job reports errors itself; this is a last guard
        out.record.spec = job->spec;
        out.error = e.what();
      }
      std::lock_guard lock(mutex);
      finished.push_back(std::move(out));
      wake.notify_one();
    }
  }
  // The local outcomes finished so far; waits up to `wait` for one when there are none.
  std::deque<JobOutcome> collect(std::chrono::milliseconds wait) {
    std::deque<JobOutcome> local;
    std::unique_lock lock(mutex);
    if (finished.empty() && wait.count() > 0) wake.wait_for(lock, wait);
    local.swap(finished);
    return local;
  }
  // Every job handed out is back, and none is left to hand out (or a failure stopped that).
  bool done() {
    std::lock_guard lock(mutex);
    return received == next && (failed || next == pending.size());
  }
};

std::vector<RunJob> Executor::pending_jobs(const std::vector<RunSpec>& specs, const std::string& label) const {
  std::vector<RunJob> pending;
  for (const auto& s : specs) {
    const RunRecord* stored = store_.find(s.id);
    if (!stored) {
      pending.push_back(make_job(plan_, s));
      pending.back().options.threads = threads_;
      if (s.phase == "verify" && !picture_dir_.empty()) pending.back().options.picture_path = picture_dir_ + "/" + s.id + ".png";
    }
    else if (stored->spec.x != s.x || stored->spec.seed != s.seed)
      throw std::runtime_error(store_.path() + " holds run " + s.id + " at other parameters than the campaign asks for now "
                               "(the analysis it followed changed?); start again with --new");
  }
  const int skipped = int(specs.size() - pending.size());
  if (!quiet_ && skipped > 0)
    std::fprintf(stderr, "%s: %d of %zu runs already in %s\n", label.c_str(), skipped, specs.size(), store_.path().c_str());
  return pending;
}

// Stores one outcome; a failed run or a failed insert stops handing out work, and the runs still
// in flight are stored as they finish.
void Executor::store_outcome(Batch& b, JobOutcome& out) {
  ++b.received;
  if (!out.error.empty()) return b.fail("run " + out.record.spec.id + " failed: " + out.error);
  try {
    store_.insert(out.record);
  } catch (const std::exception& e) {
    return b.fail("run " + out.record.spec.id + " finished but could not be stored: " + e.what());
  }
  ++simulated_;
  if (quiet_) return;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - b.start).count();
  double eta = elapsed / double(b.received) * double(b.pending.size() - b.received);
  std::fprintf(stderr, "%s [%zu/%zu] %s %s (%.2f s, rank %d), ETA %s\n", b.label.c_str(), b.received, b.pending.size(),
               out.record.spec.id.c_str(), describe(out.record, plan_).c_str(), out.record.wall_s, out.record.rank,
               format_duration(eta).c_str());
}

void Executor::coordinate(Batch& b) {
  const bool remote = mpi_.has_workers();
  std::vector<int>& idle_ranks = mpi_.idle_ranks();
  auto send_job = [&](int rank) {
    const RunJob* job = b.take();
    if (job) mpi_send_text(job_to_text(*job), rank, kTagJob);
    return job != nullptr;
  };
  for (;;) {
    // Ranks left waiting by an earlier batch get work first.
    while (remote && !idle_ranks.empty() && send_job(idle_ranks.back())) idle_ranks.pop_back();
    bool busy = false;
    while (remote && mpi_message_waiting()) {
      busy = true;
      int from = 0, tag = 0;
      std::string text = mpi_receive_text(MPI_ANY_SOURCE, MPI_ANY_TAG, &from, &tag);
      if (tag == kTagRequest) {
        if (!send_job(from)) idle_ranks.push_back(from);
      } else if (tag == kTagResult) {
        JobOutcome out = outcome_from_text(text);
        store_outcome(b, out);
      }
    }
    using std::chrono::milliseconds;
    for (auto& out : b.collect(busy ? milliseconds(0) : milliseconds(remote ? 1 : 200))) store_outcome(b, out);
    if (b.done()) return;
  }
}

void Executor::run(const std::vector<RunSpec>& specs, const std::string& label) {
  const std::vector<RunJob> pending = pending_jobs(specs, label);
  if (pending.empty()) return;
  Batch batch(pending, label);
  std::vector<std::thread> threads;
  for (int t = 0; t < jobs_ && t < int(pending.size()); ++t) threads.emplace_back([&] { batch.work(mpi_.rank()); });
  try {
    coordinate(batch);
  } catch (const std::exception& e) {
    // The coordinating loop itself failed (a message it could not read): the local runs in
    // flight finish and are stored before the error is reported.
    batch.fail(e.what());
  }
  for (auto& t : threads) t.join();
  for (auto& out : batch.finished) store_outcome(batch, out);
  if (batch.failed) throw std::runtime_error(batch.first_error);
}

}  // namespace repose::calibrate
