#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <omp.h>

#include "common/cuda_runtime.h"

namespace hdrf {
namespace {

// A frame's upload through staging memory: every byte arrives, at sizes around the pieces'
// boundaries and with any number of CPU threads; the device bytes around it stay as they were.
TEST(GpuUpload, EveryByteArrivesAtAnySizeAndThreadCount) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
  const std::size_t piece = std::size_t(128) << 10;
  const int threads = omp_get_max_threads();
  for (int n : {1, 2, 5, threads}) {
    omp_set_num_threads(n);
    for (std::size_t bytes : {std::size_t(0), std::size_t(1), piece - 1, piece, piece + 1, 7 * piece + 17,
                              std::size_t(640 * 480 * 4)}) {
      std::vector<std::uint8_t> src(bytes), staging(bytes), back(bytes + 64), guard(bytes + 64, 0xAB);
      for (std::size_t i = 0; i < bytes; ++i) src[i] = std::uint8_t((i * 2654435761u) >> 13);
      void* d = cuda::Malloc(bytes + 64);
      cuda::CopyHostToDevice(d, guard.data(), guard.size());
      const cuda::UploadPart part{static_cast<std::uint8_t*>(d) + 32, staging.data(), src.data(), bytes};
      cuda::UploadThroughStaging(&part, 1);
      cuda::CopyDeviceToHost(back.data(), d, back.size());
      cuda::Free(d);
      EXPECT_EQ(bytes == 0 ? 0 : std::memcmp(back.data() + 32, src.data(), bytes), 0) << bytes << " bytes, " << n << " threads";
      EXPECT_EQ(bytes == 0 ? 0 : std::memcmp(staging.data(), src.data(), bytes), 0) << bytes << " bytes";
      for (std::size_t i = 0; i < 32; ++i) {
        EXPECT_EQ(back[i], 0xAB) << bytes;
        EXPECT_EQ(back[32 + bytes + i], 0xAB) << bytes;
      }
    }
  }
  omp_set_num_threads(threads);
}

// A frame's two parts (colour and depth) in one pass: each arrives whole at its own place,
// at any thread count; the staging memory of each holds its part.
TEST(GpuUpload, TwoPartsArriveEachWhole) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
  const int threads = omp_get_max_threads();
  for (int n : {1, 2, 3, threads}) {
    omp_set_num_threads(n);
    for (const auto& [a, b] : {std::pair<std::size_t, std::size_t>{640 * 480 * 3, 640 * 480 * 4},
                               {320 * 240 * 3, 320 * 240 * 4}, {0, 1000}, {5, 0}}) {
      std::vector<std::uint8_t> src_a(a), src_b(b), st_a(a), st_b(b), back_a(a), back_b(b);
      for (std::size_t i = 0; i < a; ++i) src_a[i] = std::uint8_t((i * 2654435761u) >> 11);
      for (std::size_t i = 0; i < b; ++i) src_b[i] = std::uint8_t((i * 40503u) >> 7) ^ 0x5A;
      void* da = cuda::Malloc(a + 1);
      void* db = cuda::Malloc(b + 1);
      const cuda::UploadPart parts[2] = {{da, st_a.data(), src_a.data(), a}, {db, st_b.data(), src_b.data(), b}};
      cuda::UploadThroughStaging(parts, 2);
      cuda::CopyDeviceToHost(back_a.data(), da, a);
      cuda::CopyDeviceToHost(back_b.data(), db, b);
      cuda::Free(da);
      cuda::Free(db);
      EXPECT_TRUE(back_a == src_a) << a << " + " << b << " bytes, " << n << " threads: the first part";
      EXPECT_TRUE(back_b == src_b) << a << " + " << b << " bytes, " << n << " threads: the second part";
      EXPECT_TRUE(st_a == src_a && st_b == src_b) << a << " + " << b << " bytes: staging";
    }
  }
  omp_set_num_threads(threads);
}

// The least time of a stage as the pipeline times it: above nothing, below a millisecond, and
// longer with eight launches one behind another than with one (each queued operation costs
// device time); none asked for, none taken.
TEST(GpuRuntime, LeastStageTimeGrowsWithItsLaunches) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
  const double one = CudaLeastStageSeconds(1), eight = CudaLeastStageSeconds(8);
  std::printf("least stage: 1 launch %.2f us, 8 launches %.2f us\n", 1e6 * one, 1e6 * eight);
  EXPECT_GT(one, 0.0);
  EXPECT_LT(one, 1e-3);
  EXPECT_GT(eight, one);
  EXPECT_LT(eight, 8e-3);
  EXPECT_EQ(CudaLeastStageSeconds(0), 0.0);
}

}  // namespace
}  // namespace hdrf
