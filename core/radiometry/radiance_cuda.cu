#include "common/cuda_check.h"
#include "common/device_buffer.h"
#include "radiometry/radiance.h"
#include "radiometry/radiance_impl.h"

namespace hdrf::radiometry::detail {
namespace {
__global__ void RadianceKernel(const Rgb8* color, const float* inv_tables, float inv_exposure,
                               Float3* out, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) out[i] = PixelRadiance(color[i], inv_tables, inv_exposure);
}
}  // namespace

void ConvertToRadianceCuda(const ColorImage& color, const float* inv_tables, float inv_exposure,
                           RadianceImage& out) {
  const int n = int(color.size());
  DeviceBuffer<Rgb8> d_color;
  d_color.Upload(color.data(), color.size());
  DeviceBuffer<float> d_tables;
  d_tables.Upload(inv_tables, 3 * 256);
  DeviceBuffer<Float3> d_out(color.size());
  const int block = 256;
  RadianceKernel<<<(n + block - 1) / block, block>>>(d_color.data(), d_tables.data(),
                                                      inv_exposure, d_out.data(), n);
  HDRF_CUDA_CHECK_LAUNCH();
  d_out.Download(out.data());
}

}  // namespace hdrf::radiometry::detail
