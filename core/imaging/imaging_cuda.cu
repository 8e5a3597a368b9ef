#include "common/parallel_cuda.cuh"
#include "imaging/imaging_driver.h"

namespace hdrf::imaging {

namespace {
// The tables in shared memory, copied from device memory by the block's threads: passed as
// a kernel parameter they sat in constant memory, where the bins a warp's pixels look up
// (each its own depth differences) are read one after another (40 us at 640x480 on an H200,
// against 7 for the whole frame's conversion to radiance).
__global__ void BilateralKernel(ImageView<const float> depth_m, const BilateralTables* t, ImageView<float> out) {
  __shared__ BilateralTables s;
  static_assert(sizeof(BilateralTables) % sizeof(unsigned) == 0);
  const unsigned* from = reinterpret_cast<const unsigned*>(t);
  unsigned* to = reinterpret_cast<unsigned*>(&s);
  for (int i = threadIdx.y * blockDim.x + threadIdx.x; i < int(sizeof(BilateralTables) / sizeof(unsigned));
       i += blockDim.x * blockDim.y)
    to[i] = from[i];
  __syncthreads();
  const int x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x < depth_m.width && y < depth_m.height) out(x, y) = BilateralPixel(depth_m, s, x, y);
}
}  // namespace

void BilateralFilterOnGpu(ImageView<const float> depth_m, const BilateralTables* tables, ImageView<float> out) {
  if (depth_m.width <= 0 || depth_m.height <= 0) return;
  const dim3 block(32, 8), grid((depth_m.width + 31) / 32, (depth_m.height + 7) / 8);
  BilateralKernel<<<grid, block>>>(depth_m, tables, out);
  HDRF_CUDA_CHECK_LAUNCH();
}

void RawIntensityOnGpu(ImageView<const Rgb8> color, ImageView<float> intensity, ImageView<float> weight) {
  RawIntensity(par::Gpu{}, color, intensity, weight);
}

}  // namespace hdrf::imaging
