#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>

#include <algorithm>

#include "common/parallel_cuda.cuh"
#include "exposure/exposure_gpu.h"
#include "tracking/tracking.h"

namespace hdrf::exposure {

GpuExposureEstimator::GpuExposureEstimator(int width, int height, const ExposureOptions& o)
    : o_(o), sw_((width + o.stride - 1) / o.stride), sh_((height + o.stride - 1) / o.stride), pose_(1) {
  const std::size_t ns = std::size_t(sw_) * std::size_t(sh_);
  keys_ = DeviceBuffer<float>(ns);
  vals_ = DeviceBuffer<float>(ns);
  keys_sorted_ = DeviceBuffer<float>(ns);
  vals_sorted_ = DeviceBuffer<float>(ns);
  cum_ = DeviceBuffer<double>(ns);
  out_ = DeviceBuffer<double>(2);
  std::size_t sort_bytes = 0, cum_bytes = 0;
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, sort_bytes, keys_.data(), keys_sorted_.data(),
                                                  vals_.data(), vals_sorted_.data(), int(ns)));
  HDRF_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, cum_bytes, cum_.data(), cum_.data(), int(ns)));
  temp_ = DeviceBuffer<std::uint8_t>(std::max({sort_bytes, cum_bytes, std::size_t(16)}));
  HDRF_CUDA_CHECK(cudaMallocHost(&host_pose_, sizeof(tracking::PoseD)));
  HDRF_CUDA_CHECK(cudaMallocHost(&host_out_, 2 * sizeof(double)));
}

GpuExposureEstimator::~GpuExposureEstimator() {
  cudaFreeHost(host_out_);
  cudaFreeHost(host_pose_);
}

ExposureEstimate GpuExposureEstimator::Estimate(const ExposureArgs& a, const Pose& T_world_live) {
  *host_pose_ = tracking::ToPoseD(T_world_live);
  HDRF_CUDA_CHECK(cudaMemcpyAsync(pose_.data(), host_pose_, sizeof(tracking::PoseD), cudaMemcpyHostToDevice, 0));
  Queue(a, pose_.data(), 0);
  HDRF_CUDA_CHECK(cudaStreamSynchronize(0));
  return Result();
}

void GpuExposureEstimator::Queue(const ExposureArgs& a, const tracking::PoseD* T_world_live, cudaStream_t stream) {
  const int stride = o_.stride, sw = sw_, sh = sh_, n = sw * sh;
  float *keys = keys_.data(), *vals = vals_.data();
  const par::Gpu g{stream};
  par::ForEachPixel(g, sw, sh, [=] __device__(int x, int y) {
    ExposureArgs b = a;
    b.T_live_world = tracking::ToRigid(tracking::Inverse(*T_world_live));
    float lr, wt;
    const int i = y * sw + x;
    if (ExposureSample(b, stride * x, stride * y, &lr, &wt)) {
      keys[i] = lr;
      vals[i] = wt;
    } else {
      keys[i] = INFINITY;  // sorts after every valid sample
      vals[i] = 0.f;
    }
  });
  std::size_t bytes = temp_.size();
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp_.data(), bytes, keys_.data(), keys_sorted_.data(),
                                                  vals_.data(), vals_sorted_.data(), n, 0, int(8 * sizeof(float)),
                                                  stream));
  const float *ks = keys_sorted_.data(), *vs = vals_sorted_.data();
  double* cum = cum_.data();
  par::ForEach(g, n, [=] __device__(int i) { cum[i] = vs[i]; });
  bytes = temp_.size();
  HDRF_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp_.data(), bytes, cum, cum, n, stream));
  double* out = out_.data();
  HDRF_CUDA_CHECK(cudaMemsetAsync(out, 0, 2 * sizeof(double), stream));
  // Valid samples are the finite keys at the front; the median is the first sample whose
  // cumulative weight reaches half of the total.
  par::ForEach(g, n, [=] __device__(int i) {
    if (isfinite(ks[i]) && (i + 1 == n || !isfinite(ks[i + 1]))) out[0] = double(i + 1);
  });
  par::ForEach(g, n, [=] __device__(int i) {
    const int count = int(out[0]);
    if (i >= count) return;
    const double half = 0.5 * cum[count - 1];
    if (cum[i] >= half && (i == 0 || cum[i - 1] < half)) out[1] = exp(double(ks[i]));
  });
  HDRF_CUDA_CHECK(cudaMemcpyAsync(host_out_, out, 2 * sizeof(double), cudaMemcpyDeviceToHost, stream));
}

ExposureEstimate GpuExposureEstimator::Result() const {
  ExposureEstimate e;
  e.samples = long(host_out_[0]);
  if (e.samples < o_.min_samples) return e;
  e.ratio = host_out_[1];
  e.valid = true;
  return e;
}

}  // namespace hdrf::exposure
