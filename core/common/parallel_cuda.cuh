// The parallel primitives on the GPU (see parallel.h): kernel launches of a per-index or
// per-pixel lambda, and a deterministic sum of per-pixel contributions. Included by .cu
// files only.
#pragma once

#include <algorithm>

#include "common/cuda_check.h"
#include "common/device_buffer.h"
#include "common/parallel.h"

namespace hdrf::par {

// Kernels go to `stream` (the default stream unless a caller names another).
struct Gpu {
  cudaStream_t stream = nullptr;
};

namespace detail {
template <typename F>
__global__ void IndexKernel(int n, F f) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) f(i);
}
template <typename F>
__global__ void PixelKernel(int w, int h, F f) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x < w && y < h) f(x, y);
}
}  // namespace detail

template <typename F>
void ForEach(Gpu g, int n, F f) {
  if (n <= 0) return;
  detail::IndexKernel<<<(n + 255) / 256, 256, 0, g.stream>>>(n, f);
  HDRF_CUDA_CHECK_LAUNCH();
}

namespace detail {
template <typename F>
void LaunchPixels(Gpu g, int w, int h, dim3 block, F f) {
  if (w <= 0 || h <= 0) return;
  const dim3 grid((w + block.x - 1) / block.x, (h + block.y - 1) / block.y);
  PixelKernel<<<grid, block, 0, g.stream>>>(w, h, f);
  HDRF_CUDA_CHECK_LAUNCH();
}
}  // namespace detail

template <typename F>
void ForEachPixel(Gpu g, int w, int h, F f) {
  detail::LaunchPixels(g, w, h, dim3(32, 8), f);
}

// 8 x 8 pixels a block: a warp's 32 pixels are 8 x 4 (with 32 x 8, a row of 32). Measured on
// the ray cast at 640x480 (H200): 0.39 -> 0.36 ms, its rays from a warp taking more alike paths.
template <typename F>
void ForEachPixelInTiles(Gpu g, int w, int h, F f) {
  detail::LaunchPixels(g, w, h, dim3(8, 8), f);
}

// Sums over the pixels of a w x h grid of what `f(x, y, acc)` adds to an accumulator of K
// doubles (Acc has `double v[K]`): each thread sums its pixels, warps reduce by shuffles,
// each block writes one partial, and the last block adds the partials in fixed groups (the
// same sum on every run, no atomics on the values). Sum reads the result back to the host;
// SumOnDevice leaves it in device memory (device_sums()) for a kernel queued after it, so
// that a loop of sums and the steps between them runs without waiting for the host.
class Reducer {
 public:
  static constexpr int kThreads = 256;
  static constexpr int kBlocks = 264;
  explicit Reducer(int max_doubles);
  ~Reducer();
  Reducer(const Reducer&) = delete;
  Reducer& operator=(const Reducer&) = delete;

  template <typename Acc, typename F>
  Acc Sum(int w, int h, F f);
  template <typename Acc, typename F>
  void SumOnDevice(int w, int h, F f, cudaStream_t stream = 0);
  // Where SumOnDevice leaves the sums (device memory, until the next sum).
  double* device_sums() { return sums_.data(); }

 private:
  DeviceBuffer<double> partial_, sums_;
  DeviceBuffer<unsigned> done_;
  double* host_ = nullptr;  // pinned
};

namespace detail {
// The reduction's two halves, as device functions that another kernel may run for blocks of
// its own (the tracker's run does: tracking_cuda.cu), so that its sums are these bits.
// The pixels of sum block b of nb (kThreads threads each) added to this thread's `acc`.
template <typename Acc, typename F>
__device__ void AddBlockPixels(int b, int nb, int w, int h, F f, Acc& acc) {
  const int n = w * h;
  for (int i = b * Reducer::kThreads + int(threadIdx.x); i < n; i += nb * Reducer::kThreads) f(i % w, i / w, acc);
}
// The block's threads' `acc` summed (warps by shuffles, then the warps in order) into
// partial[b * K ...]; `sh` is shared memory of kThreads / 32 rows of K. Every thread calls it;
// it ends with the block synchronised.
template <typename Acc, int K = sizeof(Acc::v) / sizeof(double)>
__device__ void StoreBlockPartial(const Acc& acc, int b, double (*sh)[K], double* partial) {
  const int lane = threadIdx.x & 31, warp = threadIdx.x >> 5;
#pragma unroll
  for (int k = 0; k < K; ++k) {
    double v = acc.v[k];
    for (int off = 16; off > 0; off >>= 1) v += __shfl_down_sync(0xffffffffu, v, off);
    if (lane == 0) sh[warp][k] = v;
  }
  __syncthreads();
  if (threadIdx.x < K) {
    double s = 0;
    for (int wi = 0; wi < Reducer::kThreads / 32; ++wi) s += sh[wi][threadIdx.x];
    partial[b * K + threadIdx.x] = s;
  }
  __syncthreads();
}
// G groups of K threads each add every G-th block's partials, then one thread per value adds
// the groups' sums in group order, into out[0..K): the same order every run, G times shorter
// chains. Loads through L2 (the other blocks' stores are there, not in this block's L1):
// unlike volatile loads, the compiler may issue them ahead of the additions, which keep
// their order. Every thread calls it; it ends with the block synchronised.
template <int K>
constexpr int kPartialGroups = Reducer::kThreads / K > 0 ? Reducer::kThreads / K : 1;
template <int K>
__device__ void AddPartials(int nb, const double* partial, double (*group_sum)[K], double* out) {
  constexpr int G = kPartialGroups<K>;
  if (threadIdx.x < G * K) {
    const int k = threadIdx.x % K, grp = threadIdx.x / K;
    double s = 0;
#pragma unroll 8
    for (int b = grp; b < nb; b += G) s += __ldcg(partial + b * K + k);
    group_sum[grp][k] = s;
  }
  __syncthreads();
  if (threadIdx.x < K) {
    double s = 0;
    for (int grp = 0; grp < G; ++grp) s += group_sum[grp][threadIdx.x];
    out[threadIdx.x] = s;
  }
  __syncthreads();
}

template <typename Acc, typename F>
__global__ void __launch_bounds__(Reducer::kThreads)
    SumKernel(int w, int h, F f, double* partial, unsigned* done, double* out) {
  constexpr int K = sizeof(Acc::v) / sizeof(double);
  Acc acc;
  AddBlockPixels(int(blockIdx.x), int(gridDim.x), w, h, f, acc);
  __shared__ double sh[Reducer::kThreads / 32][K];
  StoreBlockPartial(acc, int(blockIdx.x), sh, partial);
  // The last block to finish adds the partials, in block order (the same sum every run).
  __shared__ bool last;
  __threadfence();
  __syncthreads();
  if (threadIdx.x == 0) last = atomicAdd(done, 1u) == gridDim.x - 1;
  __syncthreads();
  if (!last) return;
  __threadfence();
  __shared__ double group_sum[kPartialGroups<K>][K];
  AddPartials<K>(int(gridDim.x), partial, group_sum, out);
  if (threadIdx.x == 0) *done = 0;  // ready for the next reduction
}
}  // namespace detail

inline Reducer::Reducer(int max_doubles)
    : partial_(std::size_t(kBlocks) * std::size_t(max_doubles)), sums_(std::size_t(max_doubles)), done_(1) {
  HDRF_CUDA_CHECK(cudaMemset(done_.data(), 0, sizeof(unsigned)));
  HDRF_CUDA_CHECK(cudaMallocHost(&host_, sizeof(double) * std::size_t(max_doubles)));
}
inline Reducer::~Reducer() { cudaFreeHost(host_); }

template <typename Acc, typename F>
Acc Reducer::Sum(int w, int h, F f) {
  constexpr int K = sizeof(Acc::v) / sizeof(double);
  const int blocks = std::max(1, std::min(kBlocks, (w * h + kThreads - 1) / kThreads));
  detail::SumKernel<Acc><<<blocks, kThreads>>>(w, h, f, partial_.data(),
                                                done_.data(), sums_.data());
  HDRF_CUDA_CHECK_LAUNCH();
  HDRF_CUDA_CHECK(cudaMemcpyAsync(host_, sums_.data(), sizeof(double) * K, cudaMemcpyDeviceToHost, 0));
  HDRF_CUDA_CHECK(cudaStreamSynchronize(0));
  Acc out;
  for (int k = 0; k < K; ++k) out.v[k] = host_[k];
  return out;
}

template <typename Acc, typename F>
void Reducer::SumOnDevice(int w, int h, F f, cudaStream_t stream) {
  const int blocks = std::max(1, std::min(kBlocks, (w * h + kThreads - 1) / kThreads));
  detail::SumKernel<Acc><<<blocks, kThreads, 0, stream>>>(w, h, f, partial_.data(), done_.data(),
                                                          sums_.data());
  HDRF_CUDA_CHECK_LAUNCH();
}

}  // namespace hdrf::par
