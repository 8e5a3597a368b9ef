#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include <omp.h>

#include "common/parallel_copy.h"

namespace hdrf {
namespace {

// Every byte arrives, at sizes around the chunk boundaries and with any number of threads;
// the bytes around the destination stay as they were.
TEST(ParallelCopy, CopiesEveryByteAtAnySizeAndThreadCount) {
  const std::size_t chunk = std::size_t(256) << 10;
  const int threads = omp_get_max_threads();
  for (int n : {1, 2, 3}) {
    omp_set_num_threads(n);
    for (std::size_t bytes : {std::size_t(0), std::size_t(1), chunk - 1, chunk, chunk + 1, 3 * chunk + 17,
                              std::size_t(640 * 480 * 4)}) {
      std::vector<std::uint8_t> src(bytes), dst(bytes + 64, 0xAB);
      for (std::size_t i = 0; i < bytes; ++i) src[i] = std::uint8_t((i * 2654435761u) >> 13);
      ParallelCopy(dst.data() + 32, src.data(), bytes);
      EXPECT_EQ(bytes == 0 ? 0 : std::memcmp(dst.data() + 32, src.data(), bytes), 0) << bytes << " bytes, " << n << " threads";
      for (std::size_t i = 0; i < 32; ++i) {
        EXPECT_EQ(dst[i], 0xAB) << bytes;
        EXPECT_EQ(dst[32 + bytes + i], 0xAB) << bytes;
      }
    }
  }
  omp_set_num_threads(threads);
}

}  // namespace
}  // namespace hdrf
