// Builds without CUDA: the GPU entry points of the tone-mapping operators say so.
#include "common/cuda_runtime.h"
#include "tonemap/mantiuk06/mantiuk06.h"
#include "tonemap/mantiuk08/mantiuk08.h"

namespace hdrf::tonemap {

namespace m08 {
struct CudaWorkspace::Impl {};
CudaWorkspace::CudaWorkspace() { ThrowNoCudaBackend(); }
CudaWorkspace::~CudaWorkspace() = default;
void CudaWorkspace::Upload(const RadianceImage&) { ThrowNoCudaBackend(); }
Density CudaWorkspace::ComputeDensity(float, int) { ThrowNoCudaBackend(); }
void CudaWorkspace::Apply(const CurveLut&, Image<Float3>&) { ThrowNoCudaBackend(); }
}  // namespace m08

namespace m06 {
Result MapCuda(const RadianceImage&, Image<Float3>&, const Options&) { ThrowNoCudaBackend(); }
struct CudaWorkspace::Impl {};
CudaWorkspace::CudaWorkspace() { ThrowNoCudaBackend(); }
CudaWorkspace::~CudaWorkspace() = default;
Result CudaWorkspace::Map(const RadianceImage&, Image<Float3>&, const Options&) { ThrowNoCudaBackend(); }
}  // namespace m06

}  // namespace hdrf::tonemap
