// Independent jobs over a few threads: each thread takes the next index not yet taken, so long
// and short jobs share out evenly; the caller's thread is one of them.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace repose {

// Calls body(i) for every i in [0, n) on up to `threads` threads. When all have finished, rethrows
// the first exception a call threw (the other calls still ran).
template <class Body>
void parallel_each(size_t n, unsigned threads, Body body) {
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&] {
    for (size_t i = next++; i < n; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> helpers;
  for (size_t t = 1; t < std::min<size_t>(threads, n); ++t) helpers.emplace_back(worker);
  worker();
  for (auto& h : helpers) h.join();
  if (error) std::rethrow_exception(error);
}

// memcpy in blocks of `block` bytes on up to `threads` threads: one thread's memcpy moves ~10 GB/s,
// less than a server's memory or a GPU's bus (a mapped or staging buffer's transfers, host/vk).
inline void parallel_copy(void* to, const void* from, size_t bytes, unsigned threads, size_t block = size_t(4) << 20) {
  const size_t blocks = (bytes + block - 1) / block;
  if (blocks < 2 || threads < 2) return (void)std::memcpy(to, from, bytes);
  parallel_each(blocks, threads, [&](size_t b) {
    const size_t at = b * block;
    std::memcpy(static_cast<char*>(to) + at, static_cast<const char*>(from) + at, std::min(block, bytes - at));
  });
}

// std::sort of v on up to `threads` threads: a power of two of parts sorted at once, then merged
// pairwise, a level at a time. For a total order (no two elements equivalent) the result is
// std::sort's, whatever the threads.
template <class T>
void parallel_sort(std::vector<T>& v, unsigned threads, size_t least_part = size_t(1) << 16) {
  size_t parts = 1;
  while (parts * 2 <= threads && v.size() / (parts * 2) >= least_part) parts *= 2;
  auto bound = [&](size_t i) { return v.begin() + std::ptrdiff_t(i * v.size() / parts); };
  parallel_each(parts, threads, [&](size_t i) { std::sort(bound(i), bound(i + 1)); });
  for (size_t width = 1; width < parts; width *= 2)
    parallel_each(parts / (2 * width), threads, [&](size_t k) {
      std::inplace_merge(bound(2 * width * k), bound(2 * width * k + width), bound(2 * width * (k + 1)));
    });
}

}  // namespace repose
