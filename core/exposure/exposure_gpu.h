// Exposure compensation on the GPU (exposure_cuda.cu): the same samples (exposure_impl.h)
// and the same confidence-weighted median as EstimateExposureRatio, found by a radix select
// over the keys' bits with the weights summed exactly (no sort). Built only with CUDA; the
// buffers are sized once for the frame.
//
// The live frame's pose reaches the device as doubles, and the transform the samples use is
// made from it there: an estimate queued behind the tracker's run, at the pose the run leaves
// in device memory (Queue), is the one Estimate makes at that pose read back, bit for bit.
#pragma once

#include <cuda_runtime_api.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "common/device_buffer.h"
#include "exposure/exposure.h"
#include "tracking/gn_step.h"

namespace hdrf::exposure {

class GpuExposureEstimator;
// WeightedMedianRatio (exposure.h) on the GPU, through the estimator's own selection: for tests.
ExposureEstimate GpuWeightedMedianRatio(const std::vector<std::pair<float, float>>& samples, int min_samples = 50);

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
  friend ExposureEstimate GpuWeightedMedianRatio(const std::vector<std::pair<float, float>>&, int);
  // The selection over n samples, queued on `stream`: make(i, &key, &weight) makes sample i
  // (exposure_cuda.cu; weight 0: none), and the first pass stores it in keys_ and weights_.
  template <typename Make>
  void QueueSelect(int n, Make make, cudaStream_t stream);
  ExposureOptions o_;
  int sw_ = 0, sh_ = 0;  // the sample grid (every stride-th pixel)
  DeviceBuffer<unsigned> keys_;                  // each sample's key, as ordered bits
  DeviceBuffer<unsigned long long> weights_;     // its weight in fixed point; 0: no sample
  DeviceBuffer<unsigned long long> bins_;        // each pass's bins (zero between selections)
  DeviceBuffer<std::uint8_t> state_;             // the samples' count (zero between selections)
  DeviceBuffer<double> out_;                     // (count, ratio, log ratio)
  DeviceBuffer<tracking::PoseD> pose_;  // Estimate's pose, on the device
  tracking::PoseD* host_pose_ = nullptr;  // pinned
  double* host_out_ = nullptr;           // pinned: out, read back
};

}  // namespace hdrf::exposure
