// Normalized radiance on the GPU: the shared driver (normalized_radiance_driver.h) with
// par::Gpu, and the GPU's own row and column passes of the integral images.
#include "common/parallel_cuda.cuh"
#include "normalized_radiance/normalized_radiance_driver.h"

namespace hdrf::nr {

namespace {
// One block per row stages the row in shared memory (coalesced); three warps run NrRowPass's
// sequential sums, one sum each (the count, the values, their squares: the same additions in
// the same order), one thread of each, each warp with only its own sum's instructions (as
// three threads of one warp, each element's three terms were chosen between in step); all
// threads write back. Each summing thread reads kRowAhead cells into registers before it adds
// them: read one at a time between its stores to shared memory (which the compiler must
// assume may be the cells), each cell waited for the shared memory's latency (18 us a row
// pass at 640x480 on an H100).
constexpr int kRowAhead = 16;
template <int kWhich>  // 0: the count of cells with a value, 1: the values, 2: their squares
__device__ void RowSums(const float* m, int sw, double* out) {
  double acc = 0;
  out[0] = 0;
  for (int x0 = 0; x0 < sw; x0 += kRowAhead) {
    float c[kRowAhead];
#pragma unroll
    for (int k = 0; k < kRowAhead; ++k) c[k] = x0 + k < sw ? m[x0 + k] : 0.f;
#pragma unroll
    for (int k = 0; k < kRowAhead; ++k) {
      if (x0 + k >= sw) break;
      const double v = c[k];
      acc += kWhich == 0 ? (v > 0 ? 1.0 : 0.0) : kWhich == 1 ? v : v * v;
      out[x0 + k + 1] = acc;
    }
  }
}
__global__ void RowPassKernel(ImageView<const float> cells, NrIntegrals in) {
  extern __shared__ double smem[];
  const int sw = cells.width, y = blockIdx.x;
  // count, values, squares side by side (each thread's row computed from smem, not taken from
  // a local array, so that its stores stay shared-memory stores)
  float* m = reinterpret_cast<float*>(smem + 3 * (sw + 1));
  for (int x = threadIdx.x; x < sw; x += blockDim.x) m[x] = cells(x, y);
  __syncthreads();
  if (threadIdx.x % 32 == 0) {
    const int which = int(threadIdx.x) / 32;  // (the same for the whole warp)
    double* out = smem + which * (sw + 1);
    if (which == 0) RowSums<0>(m, sw, out);
    else if (which == 1) RowSums<1>(m, sw, out);
    else if (which == 2) RowSums<2>(m, sw, out);
  }
  __syncthreads();
  for (int x = threadIdx.x; x <= sw; x += blockDim.x) {
    in.cnt(x, y + 1) = smem[x];
    in.s1(x, y + 1) = smem[(sw + 1) + x];
    in.s2(x, y + 1) = smem[2 * (sw + 1) + x];
  }
}
// The column pass (NrColumnPass) with one thread per column and per sum (count, sum,
// squares: the three are independent), each reading the next kColumnAhead entries while it
// adds the ones it holds: the same additions in the same order. (As one thread per column
// with all three, 2 blocks waited on memory 30 times a column: 40 us at 640x480 on an H200,
// twice a frame; reading 16 ahead and then adding, each 16 still waited: 10.5 us on an H100.)
constexpr int kColumnAhead = 16;
__global__ void ColumnPassKernel(NrIntegrals in) {
  const int w = in.cnt.width, h = in.cnt.height;
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= 3 * w) return;
  const int x = t % w, which = t / w;
  const ImageView<double> img = which == 0 ? in.cnt : which == 1 ? in.s1 : in.s2;
  img(x, 0) = 0;
  double acc = 0;
  double v[kColumnAhead];
#pragma unroll
  for (int k = 0; k < kColumnAhead; ++k) v[k] = 1 + k < h ? img(x, 1 + k) : 0.0;
  for (int y0 = 1; y0 < h; y0 += kColumnAhead) {
    double next[kColumnAhead];  // read before this run's sums are stored
#pragma unroll
    for (int k = 0; k < kColumnAhead; ++k) {
      const int yn = y0 + kColumnAhead + k;
      next[k] = yn < h ? img(x, yn) : 0.0;
    }
#pragma unroll
    for (int k = 0; k < kColumnAhead; ++k) {
      if (y0 + k >= h) break;
      acc += v[k];
      img(x, y0 + k) = acc;
    }
#pragma unroll
    for (int k = 0; k < kColumnAhead; ++k) v[k] = next[k];
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
