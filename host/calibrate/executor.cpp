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
  auto it = r.responses.find(plan.response);
  if (it != r.responses.end()) {
    std::snprintf(buf, sizeof buf, " -> %s=%.6g", plan.response.c_str(), it->second);
    s += buf;
  }
  return s;
}

}  // namespace

Executor::Executor(const CampaignPlan& plan, RunStore& store, MpiSession& mpi, int jobs, bool quiet, unsigned threads)
    : plan_(plan), store_(store), mpi_(mpi), jobs_(jobs), quiet_(quiet), threads_(std::max(1u, threads)) {
  if (jobs_ < 1 && !mpi_.has_workers()) jobs_ = 1;
}

void Executor::run(const std::vector<RunSpec>& specs, const std::string& label) {
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
  if (pending.empty()) return;

  const bool remote = mpi_.has_workers();
  std::vector<int>& idle_ranks = mpi_.idle_ranks();
  std::mutex mutex;
  std::condition_variable wake;
  size_t next = 0;
  bool failed = false;
  std::deque<JobOutcome> finished;
  std::string first_error;
  // Hands out the next job unless a run failed; called with the mutex held.
  auto take = [&]() -> const RunJob* { return (!failed && next < pending.size()) ? &pending[next++] : nullptr; };
  auto fail = [&](const std::string& error) {
    std::lock_guard lock(mutex);
    if (!failed) first_error = error;
    failed = true;
  };

  std::vector<std::thread> threads;
  for (int t = 0; t < jobs_ && t < int(pending.size()); ++t)
    threads.emplace_back([&] {
      for (;;) {
        const RunJob* job;
        {
          std::lock_guard lock(mutex);
          job = take();
        }
        if (!job) return;
        JobOutcome out;
        try {
          out = execute_job(*job, mpi_.rank());
        } catch (const std::exception& e) {  // execute_job reports errors itself; this is a last guard
          out.record.spec = job->spec;
          out.error = e.what();
        }
        std::lock_guard lock(mutex);
        finished.push_back(std::move(out));
        wake.notify_one();
      }
    });

  size_t received = 0;
  const auto start = std::chrono::steady_clock::now();
  // Stores one outcome; a failed run or a failed insert stops handing out work, and the runs
  // still in flight are stored as they finish.
  auto store_outcome = [&](JobOutcome& out) {
    ++received;
    if (!out.error.empty()) return fail("run " + out.record.spec.id + " failed: " + out.error);
    try {
      store_.insert(out.record);
    } catch (const std::exception& e) {
      return fail("run " + out.record.spec.id + " finished but could not be stored: " + e.what());
    }
    ++simulated_;
    if (quiet_) return;
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double eta = elapsed / double(received) * double(pending.size() - received);
    std::fprintf(stderr, "%s [%zu/%zu] %s %s (%.2f s, rank %d), ETA %s\n", label.c_str(), received, pending.size(),
                 out.record.spec.id.c_str(), describe(out.record, plan_).c_str(), out.record.wall_s, out.record.rank,
                 format_duration(eta).c_str());
  };
  auto send_job = [&](int rank) -> bool {
    const RunJob* job;
    {
      std::lock_guard lock(mutex);
      job = take();
    }
    if (!job) return false;
    mpi_send_text(job_to_text(*job), rank, kTagJob);
    return true;
  };

  try {
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
          store_outcome(out);
        }
      }
      std::deque<JobOutcome> local;
      {
        std::unique_lock lock(mutex);
        if (finished.empty() && !busy)
          wake.wait_for(lock, std::chrono::milliseconds(remote ? 1 : 200));
        local.swap(finished);
      }
      for (auto& out : local) store_outcome(out);
      size_t handed;
      {
        std::lock_guard lock(mutex);
        handed = next;
      }
      if (received == handed && (failed || handed == pending.size())) break;
    }
  } catch (const std::exception& e) {
    // The coordinating loop itself failed (a message it could not read): the local runs in
    // flight finish and are stored before the error is reported.
    fail(e.what());
  }
  for (auto& t : threads) t.join();
  for (auto& out : finished) store_outcome(out);
  if (failed) throw std::runtime_error(first_error);
}

}  // namespace repose::calibrate
