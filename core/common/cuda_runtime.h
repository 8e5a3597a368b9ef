// The CUDA runtime as the rest of the core sees it: whether a GPU can be used, and raw
// device memory. Without a CUDA build every call that needs the GPU throws hdrf::Error
// saying so, so call sites need no #ifdef.
#pragma once

#include <cstddef>
#include <string>

namespace hdrf {

enum class Device { kCpu, kCuda };

inline const char* DeviceName(Device d) { return d == Device::kCuda ? "cuda" : "cpu"; }

// True when this build has the CUDA backend and a usable GPU is present. When false and
// `why` is given, it receives a one-line reason a user can act on.
bool CudaAvailable(std::string* why = nullptr);

// Throws hdrf::Error explaining that this build has no CUDA backend.
[[noreturn]] void ThrowNoCudaBackend();

// Name and memory of GPU 0, for reports ("" when none).
std::string CudaDeviceDescription();

// Bytes of GPU 0's memory in use (by every process), 0 when none.
std::size_t CudaMemoryUsed();

// GPU 0's memory bandwidth as a device-to-device copy achieves it (bytes read plus bytes
// written, per second; the best of a few copies of 256 MiB), 0 when there is no GPU.
double CudaCopyBandwidth();
// Bytes per second a copy from pinned host memory to GPU 0 achieves (the best of a few copies
// of 64 MiB): the most the bus carries a frame's upload at. 0 when there is no GPU.
double CudaUploadBandwidth();
// The least time a pipeline stage takes as the stage timing measures it (the device waited for
// before and after; pipeline.h) where its device work is `operations` of the smallest one, a
// 4-byte clear, queued one behind the other: the median of 200 tries, in seconds. What no
// stage of that many launches goes below however little it moves. 0 when there is no GPU.
double CudaLeastStageSeconds(int operations);

namespace cuda {
void* Malloc(std::size_t bytes);
void Free(void* ptr) noexcept;
void CopyHostToDevice(void* dst, const void* src, std::size_t bytes);
void CopyDeviceToHost(void* dst, const void* src, std::size_t bytes);
// Queues a copy of `bytes` of ordinary host memory `src` to the device's `dst` through
// `staging` (pinned host memory as large): the CPU's threads copy pieces into the staging
// memory, and the calling thread queues each piece for the GPU (on the default stream) as
// soon as it is there, so the bus carries the first pieces while the CPU copies the rest.
// Returns once every piece is queued; the staging memory is in use until the default
// stream reaches this point. Several parts (a frame's colour and depth) go in one pass.
struct UploadPart {
  void* dst;
  void* staging;
  const void* src;
  std::size_t bytes;
};
void UploadThroughStaging(const UploadPart* parts, int count);
void Synchronize();
}  // namespace cuda

}  // namespace hdrf
