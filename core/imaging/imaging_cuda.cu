#include "common/cuda_check.h"
#include "common/device_buffer.h"
#include "imaging/imaging.h"
#include "imaging/imaging_impl.h"

namespace hdrf::imaging::detail {
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

}  // namespace hdrf::imaging::detail
