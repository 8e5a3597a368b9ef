// Normalized radiance on the GPU: the shared driver (normalized_radiance_driver.h) with
// par::Gpu, and the GPU's own row and column passes of the integral images.
#include "common/parallel_cuda.cuh"
#include "normalized_radiance/normalized_radiance_driver.h"

namespace hdrf::nr {

namespace {
// One block per row stages the row in shared memory (coalesced); three threads of a warp run
// NrRowPass's sequential sums, one sum each (the count, the values, their squares: the same
// additions in the same order), in step; all threads write back.
__global__ void RowPassKernel(ImageView<const float> cells, NrIntegrals in) {
  extern __shared__ double smem[];
  const int sw = cells.width, y = blockIdx.x;
  double* sums[3] = {smem, smem + (sw + 1), smem + 2 * (sw + 1)};  // count, values, squares
  float* m = reinterpret_cast<float*>(smem + 3 * (sw + 1));
  for (int x = threadIdx.x; x < sw; x += blockDim.x) m[x] = cells(x, y);
  __syncthreads();
  if (threadIdx.x < 3) {
    const int which = threadIdx.x;
    double* out = sums[which];
    double acc = 0;
    out[0] = 0;
    for (int x = 0; x < sw; ++x) {
      const double v = m[x];
      const double v2 = v * v;
      acc += which == 0 ? (v > 0 ? 1.0 : 0.0) : which == 1 ? v : v2;
      out[x + 1] = acc;
    }
  }
  __syncthreads();
  for (int x = threadIdx.x; x <= sw; x += blockDim.x) {
    in.cnt(x, y + 1) = sums[0][x];
    in.s1(x, y + 1) = sums[1][x];
    in.s2(x, y + 1) = sums[2][x];
  }
}
// The column pass (NrColumnPass) with one thread per column and per sum (count, sum,
// squares: the three are independent), each reading kColumnAhead entries ahead of its sums:
// the same additions in the same order. As one thread per column with all three, 2 blocks
// waited on memory 30 times a column (40 us at 640x480 on an H200, twice a frame).
constexpr int kColumnAhead = 16;
__global__ void ColumnPassKernel(NrIntegrals in) {
  const int w = in.cnt.width, h = in.cnt.height;
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= 3 * w) return;
  const int x = t % w, which = t / w;
  const ImageView<double> img = which == 0 ? in.cnt : which == 1 ? in.s1 : in.s2;
  img(x, 0) = 0;
  double acc = 0;
  for (int y0 = 1; y0 < h; y0 += kColumnAhead) {
    double v[kColumnAhead];
#pragma unroll
    for (int k = 0; k < kColumnAhead; ++k) v[k] = y0 + k < h ? img(x, y0 + k) : 0.0;
#pragma unroll
    for (int k = 0; k < kColumnAhead; ++k) {
      if (y0 + k >= h) break;
      acc += v[k];
      img(x, y0 + k) = acc;
    }
  }
}
}  // namespace

void ColumnPasses(par::Gpu, NrIntegrals in) {
  const int threads = 3 * in.cnt.width;
  ColumnPassKernel<<<(threads + 63) / 64, 64>>>(in);
  HDRF_CUDA_CHECK_LAUNCH();
}

void RowPasses(par::Gpu d, ImageView<const float> cells, NrIntegrals in) {
  const int sw = cells.width;
  const std::size_t shared = 3 * std::size_t(sw + 1) * sizeof(double) + std::size_t(sw) * sizeof(float);
  if (shared <= 48 * 1024) {
    RowPassKernel<<<cells.height, 128, shared>>>(cells, in);
    HDRF_CUDA_CHECK_LAUNCH();
  } else {  // very wide images: one thread per row
    par::ForEach(d, cells.height, [=] __device__(int y) { NrRowPass(cells, in, y); });
  }
}

void LuminanceOnGpu(ImageView<const Float3> radiance, ImageView<float> lum) {
  LuminanceOf(par::Gpu{}, radiance, lum);
}

void ClippedLuminanceOnGpu(ImageView<const Float3> radiance, Float3 clip, ImageView<float> lum) {
  ClippedLuminanceOf(par::Gpu{}, radiance, clip, lum);
}

void TrackingLuminanceOnGpu(ImageView<const Rgb8> color, ImageView<const Float3> radiance,
                            ImageView<const float> confidence, ImageView<float> lum, ImageView<float> weight) {
  TrackingLuminanceOf(par::Gpu{}, color, radiance, confidence, lum, weight);
}

void NormalizeOnGpu(ImageView<const float> lum, const Scratch& s, const NormalizedRadianceOptions& o,
                    ImageView<float> out) {
  Normalize(par::Gpu{}, lum, s, o, out);
}

}  // namespace hdrf::nr
