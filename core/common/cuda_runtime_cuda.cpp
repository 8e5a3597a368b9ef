// CUDA runtime entry points for a build with the CUDA backend (plain C++ against cudart).
#include <cuda_runtime_api.h>

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <memory>

#include "common/cuda_check.h"
#include "common/cuda_runtime.h"

namespace hdrf {

bool CudaAvailable(std::string* why) {
  int count = 0;
  const cudaError_t err = cudaGetDeviceCount(&count);
  if (err != cudaSuccess || count == 0) {
    if (why) {
      *why = err == cudaSuccess ? "no CUDA GPU is present"
                                : std::string("no usable CUDA GPU: ") + cudaGetErrorString(err);
    }
    cudaGetLastError();  // clear the sticky error so later CPU-only work is unaffected
    return false;
  }
  return true;
}

std::string CudaDeviceDescription() {
  if (!CudaAvailable()) return "";
  cudaDeviceProp prop{};
  if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) return "";
  return std::string(prop.name) + " (sm_" + std::to_string(prop.major) +
         std::to_string(prop.minor) + ", " +
         std::to_string(prop.totalGlobalMem / (1024ull * 1024ull)) + " MiB)";
}

std::size_t CudaMemoryUsed() {
  std::size_t free_b = 0, total_b = 0;
  if (cudaMemGetInfo(&free_b, &total_b) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return total_b - free_b;
}

double CudaCopyBandwidth() {
  if (!CudaAvailable()) return 0;
  constexpr std::size_t kBytes = 256ull << 20;
  void* a = cuda::Malloc(kBytes);
  void* b = nullptr;
  try {
    b = cuda::Malloc(kBytes);
  } catch (...) {
    cuda::Free(a);
    throw;
  }
  double best = 0;
  for (int k = 0; k < 5; ++k) {
    cuda::Synchronize();
    const auto t0 = std::chrono::steady_clock::now();
    HDRF_CUDA_CHECK(cudaMemcpy(b, a, kBytes, cudaMemcpyDeviceToDevice));
    cuda::Synchronize();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (k > 0 && s > 0) best = std::max(best, 2.0 * double(kBytes) / s);  // the first copy warms up
  }
  cuda::Free(a);
  cuda::Free(b);
  return best;
}

namespace cuda {
void* Malloc(std::size_t bytes) {
  void* p = nullptr;
  const cudaError_t err = cudaMalloc(&p, bytes);
  if (err != cudaSuccess) {
    cudaGetLastError();
    throw Error("cannot allocate " + std::to_string(bytes / (1024 * 1024)) +
                " MiB on the GPU: " + cudaGetErrorString(err));
  }
  return p;
}
void Free(void* ptr) noexcept {
  if (ptr) cudaFree(ptr);
}
void CopyHostToDevice(void* dst, const void* src, std::size_t bytes) {
  HDRF_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyHostToDevice));
}
void CopyDeviceToHost(void* dst, const void* src, std::size_t bytes) {
  HDRF_CUDA_CHECK(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToHost));
}
void UploadThroughStaging(void* dst, void* staging, const void* src, std::size_t bytes) {
  // Pieces of 128 KiB, dealt out to the threads in turn (the first pieces are copied first);
  // the calling thread queues each piece for the GPU, in order, as soon as it is in the
  // staging memory (only it calls CUDA: no driver lock contended, the caller's device).
  constexpr std::size_t kPiece = std::size_t(128) << 10;
  constexpr int kMaxThreads = 8;  // more copy no faster: the memory bus is the limit
  const long pieces = long((bytes + kPiece - 1) / kPiece);
  if (pieces == 0) return;
  auto* d = static_cast<unsigned char*>(dst);
  auto* st = static_cast<unsigned char*>(staging);
  const auto* s = static_cast<const unsigned char*>(src);
  const int threads = int(std::min<long>({pieces, long(omp_get_max_threads()), long(kMaxThreads)}));
  std::unique_ptr<std::atomic<bool>[]> ready(new std::atomic<bool>[std::size_t(pieces)]);
  for (long c = 0; c < pieces; ++c) ready[std::size_t(c)].store(false, std::memory_order_relaxed);
  long queued = 0;
  cudaError_t err = cudaSuccess;
  auto queue_ready = [&](bool wait) {
    while (queued < pieces) {
      if (!ready[std::size_t(queued)].load(std::memory_order_acquire)) {
        if (!wait) return;
        continue;
      }
      const std::size_t at = std::size_t(queued) * kPiece;
      if (err == cudaSuccess) err = cudaMemcpyAsync(d + at, st + at, std::min(kPiece, bytes - at), cudaMemcpyHostToDevice, 0);
      ++queued;
    }
  };
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), n = omp_get_num_threads();
    for (long c = t; c < pieces; c += n) {
      const std::size_t at = std::size_t(c) * kPiece;
      std::memcpy(st + at, s + at, std::min(kPiece, bytes - at));
      ready[std::size_t(c)].store(true, std::memory_order_release);
      if (t == 0) queue_ready(false);
    }
    if (t == 0) queue_ready(true);
  }
  HDRF_CUDA_CHECK(err);
}
void Synchronize() { HDRF_CUDA_CHECK(cudaDeviceSynchronize()); }
}  // namespace cuda

}  // namespace hdrf
