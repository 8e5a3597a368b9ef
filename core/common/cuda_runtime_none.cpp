// CUDA runtime entry points for a build without the CUDA backend.
#include "common/cuda_runtime.h"

#include "common/error.h"

namespace hdrf {

bool CudaAvailable(std::string* why) {
  if (why) *why = "this build has no CUDA backend (built without nvcc)";
  return false;
}
std::string CudaDeviceDescription() { return ""; }
std::size_t CudaMemoryUsed() { return 0; }
double CudaCopyBandwidth() { return 0; }
double CudaUploadBandwidth() { return 0; }
double CudaLeastStageSeconds(int) { return 0; }

namespace cuda {
void* Malloc(std::size_t) { ThrowNoCudaBackend(); }
void Free(void* ptr) noexcept { (void)ptr; }
void CopyHostToDevice(void*, const void*, std::size_t) { ThrowNoCudaBackend(); }
void CopyDeviceToHost(void*, const void*, std::size_t) { ThrowNoCudaBackend(); }
void UploadThroughStaging(const UploadPart*, int) { ThrowNoCudaBackend(); }
void Synchronize() { ThrowNoCudaBackend(); }
}  // namespace cuda
}  // namespace hdrf
