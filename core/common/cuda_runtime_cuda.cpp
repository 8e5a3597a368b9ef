// CUDA runtime entry points for a build with the CUDA backend (plain C++ against cudart).
#include <cuda_runtime_api.h>

#include <algorithm>
#include <chrono>

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
void Synchronize() { HDRF_CUDA_CHECK(cudaDeviceSynchronize()); }
}  // namespace cuda

}  // namespace hdrf
