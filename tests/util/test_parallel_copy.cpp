// parallel_copy: the bytes of memcpy, whatever the blocks and threads.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "util/parallel_each.h"

using repose::parallel_copy;

TEST_CASE("parallel_copy gives memcpy's bytes in blocks on several threads, a short last block included",
          "[util]") {
  const size_t bytes = 1000003;  // 244 blocks of 4096 bytes and a last one of 579
  std::vector<uint8_t> from(bytes);
  for (size_t i = 0; i < bytes; ++i) from[i] = uint8_t(i * 131 + (i >> 9));
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    for (size_t block : {size_t(4096), size_t(1) << 20, size_t(4) << 20}) {
      INFO(threads << " threads, blocks of " << block << " bytes");
      std::vector<uint8_t> to(bytes + 2, 0xAB);  // a guard byte each side
      parallel_copy(to.data() + 1, from.data(), bytes, threads, block);
      CHECK(to.front() == 0xAB);
      CHECK(to.back() == 0xAB);
      CHECK(std::equal(from.begin(), from.end(), to.begin() + 1));
    }
  }
  std::vector<uint8_t> none(1, 0xAB);
  parallel_copy(none.data(), from.data(), 0, 4, 4096);  // nothing to copy
  CHECK(none[0] == 0xAB);
}
