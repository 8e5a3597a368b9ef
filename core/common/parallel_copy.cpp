#include "common/parallel_copy.h"

#include <cstring>

#include <omp.h>

namespace hdrf {

void ParallelCopy(void* dst, const void* src, std::size_t bytes) {
  constexpr std::size_t kChunk = std::size_t(256) << 10;
  const long chunks = long((bytes + kChunk - 1) / kChunk);
  auto* d = static_cast<unsigned char*>(dst);
  const auto* s = static_cast<const unsigned char*>(src);
  if (chunks <= 1) {
    if (bytes > 0) std::memcpy(d, s, bytes);
    return;
  }
  // No more threads than chunks: waking a thread costs more than copying a chunk.
  const int threads = int(chunks < long(omp_get_max_threads()) ? chunks : long(omp_get_max_threads()));
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long c = 0; c < chunks; ++c) {
    const std::size_t at = std::size_t(c) * kChunk;
    const std::size_t n = bytes - at < kChunk ? bytes - at : kChunk;
    std::memcpy(d + at, s + at, n);
  }
}

}  // namespace hdrf
