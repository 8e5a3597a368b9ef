// The radiance conversions on the GPU. parallel_cuda.cuh comes first: the shared drivers
// name par::ForEachPixel, and its GPU overload must be declared before them.
#include "common/parallel_cuda.cuh"
#include "common/cuda_check.h"
#include "common/device_buffer.h"
#include "radiometry/radiance.h"
#include "radiometry/radiance_driver.h"
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

namespace {
__global__ void ConvertKernel(const Rgb8* color, const float* inverse, const float* pcf,
                              Float3* radiance, float* confidence, float* max_confidence, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) ConvertPixel(color[i], inverse, pcf, &radiance[i], &confidence[i], &max_confidence[i]);
}
}  // namespace
void ConvertFrameCuda(const ColorImage& color, const float* inverse, const float* pcf,
                      RadianceImage& radiance, Image<float>& confidence, Image<float>& max_confidence) {
  const int n = int(color.size());
  DeviceBuffer<Rgb8> d_color;
  d_color.Upload(color.data(), color.size());
  DeviceBuffer<float> d_inv, d_pcf;
  d_inv.Upload(inverse, 768);
  d_pcf.Upload(pcf, 768);
  DeviceBuffer<Float3> d_rad(color.size());
  DeviceBuffer<float> d_conf(color.size()), d_max(color.size());
  const int block = 256;
  ConvertKernel<<<(n + block - 1) / block, block>>>(d_color.data(), d_inv.data(), d_pcf.data(),
                                                     d_rad.data(), d_conf.data(), d_max.data(), n);
  HDRF_CUDA_CHECK_LAUNCH();
  d_rad.Download(radiance.data());
  d_conf.Download(confidence.data());
  d_max.Download(max_confidence.data());
}

}  // namespace hdrf::radiometry::detail

namespace hdrf::radiometry {

void ConvertFrameOnGpu(ImageView<const Rgb8> color, const float* inverse, const float* pcf,
                       ImageView<Float3> radiance, ImageView<float> confidence, ImageView<float> max_confidence) {
  ConvertFrameViews(par::Gpu{}, color, inverse, pcf, radiance, confidence, max_confidence);
}

}  // namespace hdrf::radiometry
