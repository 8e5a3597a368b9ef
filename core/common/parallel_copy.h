// A large host-to-host copy shared among the CPU's threads (one thread's memcpy moves a few
// GB/s; a frame handed to the GPU through pinned memory is copied there first).
#pragma once

#include <cstddef>

namespace hdrf {

// Copies `bytes` from `src` to `dst` (not overlapping), in chunks of 256 KiB spread over at
// most as many OpenMP threads as there are chunks; small copies stay on the calling thread.
void ParallelCopy(void* dst, const void* src, std::size_t bytes);

}  // namespace hdrf
