#include "common/error.h"

#include "common/cuda_runtime.h"

namespace hdrf {

std::string FormatInputMessage(const std::filesystem::path& file, int line,
                               const std::string& what) {
  std::string s = file.string();
  if (line > 0) s += ":" + std::to_string(line);
  return s + ": " + what;
}

void ThrowNoCudaBackend() {
  throw Error("this build of HDRFusion has no CUDA backend (nvcc was not found when it was "
              "configured); use --device cpu, or rebuild on a machine with the CUDA toolkit");
}

}  // namespace hdrf
