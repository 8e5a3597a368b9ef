// Normalized radiance on the GPU: the shared driver (normalized_radiance_driver.h) with
// par::Gpu, and the GPU's own row pass of the integral images.
#include "common/parallel_cuda.cuh"
#include "normalized_radiance/normalized_radiance_driver.h"

namespace hdrf::nr {

namespace {
// One block per row stages the row in shared memory (coalesced), one thread runs the same
// sequential sums as the CPU, all threads write back.
__global__ void RowPassKernel(ImageView<const float> cells, NrIntegrals in) {
  extern __shared__ double smem[];
  const int sw = cells.width, y = blockIdx.x;
  double* c = smem;
  double* a = c + 2 * (sw + 1);
  double* b = a + 2 * (sw + 1);
  float* m = reinterpret_cast<float*>(b + 2 * (sw + 1));
  for (int x = threadIdx.x; x < sw; x += blockDim.x) m[x] = cells(x, y);
  __syncthreads();
  if (threadIdx.x == 0) {
    const ImageView<const float> row{m, sw, 1};
    const NrIntegrals local{{c, sw + 1, 2}, {a, sw + 1, 2}, {b, sw + 1, 2}};
    NrRowPass(row, local, 0);  // writes entries (x, 1) of the 2-row local images
  }
  __syncthreads();
  for (int x = threadIdx.x; x <= sw; x += blockDim.x) {
    in.cnt(x, y + 1) = c[sw + 1 + x];
    in.s1(x, y + 1) = a[sw + 1 + x];
    in.s2(x, y + 1) = b[sw + 1 + x];
  }
}
}  // namespace

void RowPasses(par::Gpu d, ImageView<const float> cells, NrIntegrals in) {
  const int sw = cells.width;
  const std::size_t shared = 3 * 2 * std::size_t(sw + 1) * sizeof(double) + std::size_t(sw) * sizeof(float);
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
