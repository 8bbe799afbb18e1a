// A fixed pool of worker threads for the CPU twin: parallel_for gives each thread one contiguous
// range of [0, n), cut into a few chunks; a thread that finishes its own takes the chunks another
// has not started, so a thread the system has set aside (a busy shared machine) delays a kernel
// by one chunk, not by its whole share. Results never depend on the split (kernels only race on
// integer counters), so any thread count gives the same bytes.
// A step runs a handful of short kernels (a 10k-sphere kick is ~0.1 ms), so a worker spins for a
// while on the job counter before it sleeps on the condition variable: waking a sleeping thread
// costs tens of microseconds, more on a loaded machine.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace repose {

class ThreadPool {
 public:
  explicit ThreadPool(unsigned threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()) + 1; }
  // Calls body(begin, end) on disjoint ranges covering [0, n), the caller taking the first.
  void parallel_for(uint64_t n, const std::function<void(uint64_t, uint64_t)>& body);

 private:
  void worker_loop(unsigned index);
  void run_chunks(unsigned index, uint64_t generation);
  bool run_chunk_of(unsigned owner, uint64_t generation);
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  const std::function<void(uint64_t, uint64_t)>* job_ = nullptr;
  uint64_t job_size_ = 0;
  std::atomic<uint64_t> generation_{0};  // one more per job; workers spin on it, then sleep
  // Per thread: the job's generation (high 32 bits) and the next of its chunks to start; a chunk
  // is claimed by a compare-and-swap, so a thread still holding an earlier generation claims none.
  std::vector<std::atomic<uint64_t>> next_chunk_;
  std::atomic<unsigned> chunks_done_{0};
  unsigned sleepers_ = 0;                // guarded by mutex_
  std::atomic<bool> stopping_{false};
};

}  // namespace repose
