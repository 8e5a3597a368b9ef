#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>

#include <algorithm>

#include "common/parallel_cuda.cuh"
#include "exposure/exposure_gpu.h"

namespace hdrf::exposure {

GpuExposureEstimator::GpuExposureEstimator(int width, int height, const ExposureOptions& o)
    : o_(o), sw_((width + o.stride - 1) / o.stride), sh_((height + o.stride - 1) / o.stride) {
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
}

ExposureEstimate GpuExposureEstimator::Estimate(const ExposureArgs& a) {
  const int stride = o_.stride, sw = sw_, sh = sh_, n = sw * sh;
  float *keys = keys_.data(), *vals = vals_.data();
  par::ForEachPixel(par::Gpu{}, sw, sh, [=] __device__(int x, int y) {
    float lr, wt;
    const int i = y * sw + x;
    if (ExposureSample(a, stride * x, stride * y, &lr, &wt)) {
      keys[i] = lr;
      vals[i] = wt;
    } else {
      keys[i] = INFINITY;  // sorts after every valid sample
      vals[i] = 0.f;
    }
  });
  std::size_t bytes = temp_.size();
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp_.data(), bytes, keys_.data(), keys_sorted_.data(),
                                                  vals_.data(), vals_sorted_.data(), n));
  const float *ks = keys_sorted_.data(), *vs = vals_sorted_.data();
  double* cum = cum_.data();
  par::ForEach(par::Gpu{}, n, [=] __device__(int i) { cum[i] = vs[i]; });
  bytes = temp_.size();
  HDRF_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp_.data(), bytes, cum, cum, n));
  double* out = out_.data();
  HDRF_CUDA_CHECK(cudaMemset(out, 0, 2 * sizeof(double)));
  // Valid samples are the finite keys at the front; the median is the first sample whose
  // cumulative weight reaches half of the total.
  par::ForEach(par::Gpu{}, n, [=] __device__(int i) {
    if (isfinite(ks[i]) && (i + 1 == n || !isfinite(ks[i + 1]))) out[0] = double(i + 1);
  });
  par::ForEach(par::Gpu{}, n, [=] __device__(int i) {
    const int count = int(out[0]);
    if (i >= count) return;
    const double half = 0.5 * cum[count - 1];
    if (cum[i] >= half && (i == 0 || cum[i - 1] < half)) out[1] = exp(double(ks[i]));
  });
  double host[2];
  HDRF_CUDA_CHECK(cudaMemcpy(host, out, sizeof(host), cudaMemcpyDeviceToHost));
  ExposureEstimate e;
  e.samples = long(host[0]);
  if (e.samples < o_.min_samples) return e;
  e.ratio = host[1];
  e.valid = true;
  return e;
}

}  // namespace hdrf::exposure
