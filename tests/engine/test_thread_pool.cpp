// The CPU twin's thread pool (kernels_ref/thread_pool.h): every index of a job runs exactly once,
// whatever the thread count, and a thread held up inside its first chunk does not hold up the
// rest of its range: another thread takes the chunks it has not started.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "thread_pool.h"

using namespace repose;

TEST_CASE("thread pool: each index of a job runs once, for any thread count and size", "[engine]") {
  for (unsigned threads : {1u, 2u, 3u, 5u})
    for (uint64_t n : {1ull, 255ull, 256ull, 1000ull, 100003ull}) {
      ThreadPool pool(threads);
      std::vector<int> runs(n, 0);
      for (int job = 0; job < 3; ++job)
        pool.parallel_for(n, [&](uint64_t begin, uint64_t end) {
          for (uint64_t i = begin; i < end; ++i) ++runs[i];
        });
      INFO(threads << " threads, " << n << " indices");
      CHECK(std::count(runs.begin(), runs.end(), 3) == std::ptrdiff_t(n));
    }
}

TEST_CASE("thread pool: a thread held up in its first chunk leaves the rest of its range to the others", "[engine]") {
  ThreadPool pool(2);
  const uint64_t n = 4000;  // the second thread's range is [2000, 4000): chunks of 500
  std::mutex m;
  std::set<std::thread::id> ran_second_half;
  std::vector<int> runs(n, 0);
  const std::thread::id caller = std::this_thread::get_id();
  pool.parallel_for(n, [&](uint64_t begin, uint64_t end) {
    // The worker's first chunk stalls as a descheduled thread would.
    if (begin == 2000 && std::this_thread::get_id() != caller) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    for (uint64_t i = begin; i < end; ++i) ++runs[i];
    if (begin > 2000) {
      std::lock_guard<std::mutex> lock(m);
      ran_second_half.insert(std::this_thread::get_id());
    }
  });
  CHECK(std::count(runs.begin(), runs.end(), 1) == std::ptrdiff_t(n));
  // The caller finished its own half, then took the worker's later chunks.
  CHECK(ran_second_half.count(caller) == 1);
}
