// Exposure compensation on the GPU (exposure_cuda.cu): the same samples (exposure_impl.h)
// and the same confidence-weighted median as EstimateExposureRatio, with CUB's radix sort
// and scan. Built only with CUDA; the buffers are sized once for the frame.
#pragma once

#include <cstdint>

#include "common/device_buffer.h"
#include "exposure/exposure.h"

namespace hdrf::exposure {

class GpuExposureEstimator {
 public:
  GpuExposureEstimator(int width, int height, const ExposureOptions& o);
  // `a` holds device views of the model's ray cast and the live frame.
  ExposureEstimate Estimate(const ExposureArgs& a);

 private:
  ExposureOptions o_;
  int sw_ = 0, sh_ = 0;  // the sample grid (every stride-th pixel)
  DeviceBuffer<float> keys_, vals_, keys_sorted_, vals_sorted_;
  DeviceBuffer<double> cum_, out_;  // out: (count, ratio)
  DeviceBuffer<std::uint8_t> temp_;
};

}  // namespace hdrf::exposure
