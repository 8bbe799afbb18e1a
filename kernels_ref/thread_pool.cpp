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

// Chunks per thread's range: enough that a delayed thread leaves little behind, few enough that
// the lanes kernels' partial batches at chunk ends stay rare.
static constexpr unsigned kChunksPerThread = 4;

ThreadPool::ThreadPool(unsigned threads) : next_chunk_(threads == 0 ? 1 : threads) {
  if (threads == 0) threads = 1;
  for (auto& c : next_chunk_) c.store(0);
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

// Claims and runs the next unstarted chunk of thread `owner`'s range for this generation's job;
// false when none is left (or the job is no longer this generation's).
bool ThreadPool::run_chunk_of(unsigned owner, uint64_t generation) {
  std::atomic<uint64_t>& next = next_chunk_[owner];
  uint64_t c = next.load(std::memory_order_acquire);
  for (;;) {
    if ((c >> 32) != (generation & 0xffffffffu) || (c & 0xffffffffu) >= kChunksPerThread) return false;
    if (next.compare_exchange_weak(c, c + 1, std::memory_order_acq_rel, std::memory_order_acquire)) break;
  }
  // Claimed: the caller waits for this chunk, so the job cannot change under it.
  const uint64_t n = job_size_, parts = size(), k = c & 0xffffffffu;
  const uint64_t begin = n * owner / parts, end = n * (owner + 1) / parts;
  const uint64_t from = begin + (end - begin) * k / kChunksPerThread, to = begin + (end - begin) * (k + 1) / kChunksPerThread;
  if (from < to) (*job_)(from, to);
  chunks_done_.fetch_add(1, std::memory_order_acq_rel);
  return true;
}

// A thread's own chunks in order, then those the others have not started.
void ThreadPool::run_chunks(unsigned index, uint64_t generation) {
  while (run_chunk_of(index, generation)) {
  }
  for (unsigned d = 1; d < size(); ++d)
    while (run_chunk_of((index + d) % size(), generation)) {
    }
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
  chunks_done_.store(0, std::memory_order_relaxed);
  const uint64_t g = generation_.load(std::memory_order_relaxed) + 1;
  for (auto& c : next_chunk_) c.store((g & 0xffffffffu) << 32, std::memory_order_relaxed);
  {
    // The release publishes the job to workers that acquire the new generation; the lock orders it
    // against a worker that is about to sleep.
    std::lock_guard<std::mutex> lock(mutex_);
    generation_.store(g, std::memory_order_release);
    if (sleepers_ > 0) wake_.notify_all();
  }
  run_chunks(0, g);
  const unsigned total = size() * kChunksPerThread;
  for (int spins = 0; chunks_done_.load(std::memory_order_acquire) != total; ++spins) {
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
    run_chunks(index, g);
  }
}

}  // namespace repose
