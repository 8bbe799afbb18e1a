#include "thread_pool.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define REPOSE_PAUSE() _mm_pause()
#else
#define REPOSE_PAUSE() ((void)0)
#endif

namespace repose {

// Spin iterations before a worker sleeps (~50-100 us): longer than the gap between the kernels
// of a step, shorter than the time between batches.
static constexpr int kSpinBeforeSleep = 20000;

ThreadPool::ThreadPool(unsigned threads) {
  if (threads == 0) threads = 1;
  for (unsigned t = 1; t < threads; ++t) workers_.emplace_back([this, t] { worker_loop(t); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_.store(true);
    generation_.fetch_add(1, std::memory_order_release);
  }
  wake_.notify_all();
  for (auto& w : workers_) w.join();
}

static void run_share(const std::function<void(uint64_t, uint64_t)>& body, uint64_t n,
                      unsigned index, unsigned parts) {
  uint64_t begin = n * index / parts;
  uint64_t end = n * (index + 1) / parts;
  if (begin < end) body(begin, end);
}

void ThreadPool::parallel_for(uint64_t n, const std::function<void(uint64_t, uint64_t)>& body) {
  if (n == 0) return;
  // Small jobs are not worth handing out.
  if (workers_.empty() || n < 256) {
    body(0, n);
    return;
  }
  job_ = &body;
  job_size_ = n;
  pending_.store(static_cast<unsigned>(workers_.size()), std::memory_order_relaxed);
  {
    // The release publishes job_ to workers that acquire the new generation; the lock orders it
    // against a worker that is about to sleep.
    std::lock_guard<std::mutex> lock(mutex_);
    generation_.fetch_add(1, std::memory_order_release);
    if (sleepers_ > 0) wake_.notify_all();
  }
  run_share(body, n, 0, size());
  for (int spins = 0; pending_.load(std::memory_order_acquire) != 0; ++spins) {
    if (spins < kSpinBeforeSleep) REPOSE_PAUSE();
    else std::this_thread::yield();
  }
  job_ = nullptr;
}

void ThreadPool::worker_loop(unsigned index) {
  uint64_t seen = 0;
  for (;;) {
    uint64_t g = generation_.load(std::memory_order_acquire);
    for (int spins = 0; g == seen && spins < kSpinBeforeSleep; ++spins) {
      REPOSE_PAUSE();
      g = generation_.load(std::memory_order_acquire);
    }
    if (g == seen) {
      std::unique_lock<std::mutex> lock(mutex_);
      ++sleepers_;
      wake_.wait(lock, [&] { return generation_.load(std::memory_order_acquire) != seen; });
      --sleepers_;
      g = generation_.load(std::memory_order_acquire);
    }
    if (stopping_.load()) return;
    seen = g;
    run_share(*job_, job_size_, index, size());
    pending_.fetch_sub(1, std::memory_order_acq_rel);
  }
}

}  // namespace repose
