// CUDA runtime entry points for a build with the CUDA backend (plain C++ against cudart).
#include <cuda_runtime_api.h>

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <memory>
#include <vector>

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

double CudaUploadBandwidth() {
  if (!CudaAvailable()) return 0;
  constexpr std::size_t kBytes = 64ull << 20;
  void* host = nullptr;
  HDRF_CUDA_CHECK(cudaMallocHost(&host, kBytes));
  void* dev = nullptr;
  try {
    dev = cuda::Malloc(kBytes);
  } catch (...) {
    cudaFreeHost(host);
    throw;
  }
  std::memset(host, 1, kBytes);
  double best = 0;
  for (int k = 0; k < 5; ++k) {
    cuda::Synchronize();
    const auto t0 = std::chrono::steady_clock::now();
    const cudaError_t err = cudaMemcpy(dev, host, kBytes, cudaMemcpyHostToDevice);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (err != cudaSuccess) {
      cuda::Free(dev);
      cudaFreeHost(host);
      HDRF_CUDA_CHECK(err);
    }
    if (k > 0 && s > 0) best = std::max(best, double(kBytes) / s);  // the first copy warms up
  }
  cuda::Free(dev);
  cudaFreeHost(host);
  return best;
}

double CudaLeastStageSeconds(int operations) {
  if (!CudaAvailable() || operations < 1) return 0;
  void* word = cuda::Malloc(4);
  std::vector<double> tries;
  cudaError_t err = cudaSuccess;
  for (int k = 0; k < 210 && err == cudaSuccess; ++k) {
    err = cudaDeviceSynchronize();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < operations && err == cudaSuccess; ++i) err = cudaMemsetAsync(word, 0, 4, 0);
    if (err == cudaSuccess) err = cudaDeviceSynchronize();
    if (k >= 10) tries.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());  // (10 to warm up)
  }
  cuda::Free(word);
  HDRF_CUDA_CHECK(err);
  std::nth_element(tries.begin(), tries.begin() + std::ptrdiff_t(tries.size() / 2), tries.end());
  return tries[tries.size() / 2];
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
void UploadThroughStaging(const UploadPart* parts, int count) {
  // Pieces of 128 KiB of every part, dealt out to the copying threads in turn (the first
  // pieces are copied first); the calling thread copies none: it queues each piece for the
  // GPU, in order, as soon as it is in the staging memory (only it calls CUDA: no driver
  // lock contended, the caller's device). (Copying pieces of its own too, it left those
  // ready meanwhile unqueued.) With one thread, it copies and queues each piece in turn.
  constexpr std::size_t kPiece = std::size_t(128) << 10;
  constexpr int kMaxCopiers = 8;  // more copy no faster: the memory bus is the limit
  struct Piece {
    unsigned char* dst;
    unsigned char* staging;
    const unsigned char* src;
    std::size_t bytes;
  };
  std::vector<Piece> pieces;
  for (int p = 0; p < count; ++p)
    for (std::size_t at = 0; at < parts[p].bytes; at += kPiece)
      pieces.push_back({static_cast<unsigned char*>(parts[p].dst) + at, static_cast<unsigned char*>(parts[p].staging) + at,
                        static_cast<const unsigned char*>(parts[p].src) + at, std::min(kPiece, parts[p].bytes - at)});
  const long n = long(pieces.size());
  if (n == 0) return;
  const int threads = int(std::min<long>({n + 1, long(omp_get_max_threads()), long(kMaxCopiers + 1)}));
  cudaError_t err = cudaSuccess;
  auto queue = [&](const Piece& c) {
    if (err == cudaSuccess) err = cudaMemcpyAsync(c.dst, c.staging, c.bytes, cudaMemcpyHostToDevice, 0);
  };
  auto alone = [&] {
    for (const Piece& c : pieces) {
      std::memcpy(c.staging, c.src, c.bytes);
      queue(c);
    }
  };
  if (threads < 2) {
    alone();
    HDRF_CUDA_CHECK(err);
    return;
  }
  std::unique_ptr<std::atomic<bool>[]> ready(new std::atomic<bool>[std::size_t(n)]);
  for (long c = 0; c < n; ++c) ready[std::size_t(c)].store(false, std::memory_order_relaxed);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), copiers = omp_get_num_threads() - 1;
    if (copiers == 0) {  // (given fewer threads than asked for: inside another parallel region)
      alone();
    } else if (t == 0) {
      for (long c = 0; c < n; ++c) {
        while (!ready[std::size_t(c)].load(std::memory_order_acquire)) {
        }
        queue(pieces[std::size_t(c)]);
      }
    } else {
      for (long c = t - 1; c < n; c += copiers) {
        const Piece& p = pieces[std::size_t(c)];
        std::memcpy(p.staging, p.src, p.bytes);
        ready[std::size_t(c)].store(true, std::memory_order_release);
      }
    }
  }
  HDRF_CUDA_CHECK(err);
}
void Synchronize() { HDRF_CUDA_CHECK(cudaDeviceSynchronize()); }
}  // namespace cuda

}  // namespace hdrf
