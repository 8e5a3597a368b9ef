// Exposure compensation on the GPU (exposure_cuda.cu): the same samples (exposure_impl.h)
// and the same confidence-weighted median as EstimateExposureRatio, with CUB's radix sort
// and scan. Built only with CUDA; the buffers are sized once for the frame.
//
// The live frame's pose reaches the device as doubles, and the transform the samples use is
// made from it there: an estimate queued behind the tracker's run, at the pose the run leaves
// in device memory (Queue), is the one Estimate makes at that pose read back, bit for bit.
#pragma once

#include <cuda_runtime_api.h>

#include <cstdint>

#include "common/device_buffer.h"
#include "exposure/exposure.h"
#include "tracking/gn_step.h"

namespace hdrf::exposure {

class GpuExposureEstimator {
 public:
  GpuExposureEstimator(int width, int height, const ExposureOptions& o);
  ~GpuExposureEstimator();
  GpuExposureEstimator(const GpuExposureEstimator&) = delete;
  GpuExposureEstimator& operator=(const GpuExposureEstimator&) = delete;
  // `a` holds device views of the model's ray cast and the live frame (its T_live_world is
  // not read: the transform comes from the live frame's pose).
  ExposureEstimate Estimate(const ExposureArgs& a, const Pose& T_world_live);
  // Queued on `stream` at the pose `T_world_live` points to in device memory, nothing waited
  // for; Result() once the stream has been waited for.
  void Queue(const ExposureArgs& a, const tracking::PoseD* T_world_live, cudaStream_t stream);
  ExposureEstimate Result() const;

 private:
  ExposureOptions o_;
  int sw_ = 0, sh_ = 0;  // the sample grid (every stride-th pixel)
  DeviceBuffer<float> keys_, vals_, keys_sorted_, vals_sorted_;
  DeviceBuffer<double> cum_, out_;  // out: (count, ratio)
  DeviceBuffer<std::uint8_t> temp_;
  DeviceBuffer<tracking::PoseD> pose_;  // Estimate's pose, on the device
  tracking::PoseD* host_pose_ = nullptr;  // pinned
  double* host_out_ = nullptr;           // pinned: out, read back
};

}  // namespace hdrf::exposure
