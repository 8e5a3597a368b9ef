#include <cooperative_groups.h>

#include <algorithm>
#include <cmath>

#include "common/parallel_cuda.cuh"
#include "exposure/exposure_gpu.h"
#include "tracking/tracking.h"

namespace hdrf::exposure {

// The weighted median without sorting: the median sample's key is the smallest key k whose
// samples at or below it weigh at least half of all, so it is found by its bits, 11, 11 and
// 10 at a time (a radix select): each pass sums the weights of the samples in each bin of
// the next bits among those that share the bits found so far, and picks the bin where half
// the weight is reached. The weights are summed as integers (fixed point, 2^-40 a unit for
// up to a million samples): the sums are exact and do not depend on the order the threads
// add them in, so the pick is the one the CPU's sorted sum makes wherever its double sums
// are exact (weights of at least 2^-12 for 2^17 samples).
//
// The three passes are one cooperative launch (its blocks all resident, synchronised as a
// grid between passes), and every block makes each pick itself from the summed bins: as
// three launches, each with a last block that picked, the select took 55 us of a 640x480
// frame on an H100, mostly launches and waits.
namespace {
namespace cg = cooperative_groups;
constexpr int kThreads = 256;
constexpr int kBlocks = 132;
// Pass p's bits: 31-21, 20-10, 9-0.
__device__ int PassBits(int pass) { return pass == 2 ? 10 : 11; }
__device__ int PassShift(int pass) { return pass == 0 ? 21 : pass == 1 ? 10 : 0; }
constexpr int kMaxBins = 1 << 11;

// A float's bits as an unsigned whose order is the floats' order.
__device__ unsigned OrderedKey(float f) {
  const unsigned b = __float_as_uint(f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
__device__ float KeyFloat(unsigned u) { return __uint_as_float((u & 0x80000000u) ? (u & 0x7fffffffu) : ~u); }

// The select over n samples (key, weight; weight 0: no sample). The first pass makes them
// (`make(i, &key, &weight)`) and stores them for the others. A block sums its bins in shared
// memory as two 32-bit halves (the low half's carries added to the high half): 32-bit
// atomics are the hardware's own there, and many samples of a frame share a bin. `bins`
// holds each pass's bins and `count` the samples (zero between launches: the launch zeroes
// them after its last pick); out gets (count, ratio, log ratio).
template <typename Make>
__global__ void __launch_bounds__(kThreads)
    SelectKernel(int n, Make make, unsigned* keys, unsigned long long* weights, unsigned long long* bins,
                 unsigned long long* count, double* out) {
  const cg::grid_group grid = cg::this_grid();
  __shared__ unsigned long long sh[kMaxBins];  // the halves while summing; then the pass's bins
  unsigned* sh_lo = reinterpret_cast<unsigned*>(sh);
  unsigned* sh_hi = sh_lo + kMaxBins;
  __shared__ unsigned long long scan[kThreads];
  __shared__ unsigned long long total, below;
  __shared__ unsigned shn, prefix;  // (32 bits: a 64-bit atomic in shared memory is a loop of compare-and-swaps)
  if (threadIdx.x == 0) shn = 0, total = 0, below = 0, prefix = 0;
  for (int pass = 0; pass < 3; ++pass) {
    const int bits = PassBits(pass), shift = PassShift(pass), nbins = 1 << bits;
    unsigned long long* pass_bins = bins + pass * kMaxBins;
    for (int b = threadIdx.x; b < nbins; b += kThreads) sh_lo[b] = sh_hi[b] = 0;
    __syncthreads();
    const unsigned want = prefix;
    unsigned mine = 0;
    for (int i = blockIdx.x * kThreads + threadIdx.x; i < n; i += gridDim.x * kThreads) {
      unsigned k;
      unsigned long long w;
      if (pass == 0) {
        make(i, &k, &w);
        keys[i] = k;
        weights[i] = w;
      } else {
        w = weights[i];
        k = keys[i];
      }
      if (w == 0) continue;
      if (pass > 0 && (k >> (shift + bits)) != want) continue;
      const unsigned b = (k >> shift) & unsigned(nbins - 1), lo = unsigned(w);
      const unsigned hi = unsigned(w >> 32) + (atomicAdd(&sh_lo[b], lo) > 0xffffffffu - lo ? 1u : 0u);
      if (hi) atomicAdd(&sh_hi[b], hi);
      ++mine;
    }
    if (pass == 0) {  // the block's samples: a warp's sum, then one atomic a warp
      for (int off = 16; off > 0; off >>= 1) mine += __shfl_down_sync(0xffffffffu, mine, off);
      if (threadIdx.x % 32 == 0 && mine) atomicAdd(&shn, mine);
    }
    __syncthreads();
    for (int b = threadIdx.x; b < nbins; b += kThreads) {
      const unsigned long long v = (static_cast<unsigned long long>(sh_hi[b]) << 32) + sh_lo[b];
      if (v) atomicAdd(&pass_bins[b], v);
    }
    if (pass == 0 && threadIdx.x == 0 && shn) atomicAdd(count, static_cast<unsigned long long>(shn));
    grid.sync();
    // Every block picks: each thread's run of bins, its sum, the sums of the runs before it.
    const int per = nbins / kThreads;  // 8 or 4
    unsigned long long run = 0;
    for (int j = 0; j < per; ++j) {
      const int b = threadIdx.x * per + j;
      sh[b] = __ldcg(pass_bins + b);
      run += sh[b];
    }
    scan[threadIdx.x] = run;
    __syncthreads();
    for (int off = 1; off < kThreads; off <<= 1) {
      const unsigned long long add = threadIdx.x >= off ? scan[threadIdx.x - off] : 0;
      __syncthreads();
      scan[threadIdx.x] += add;
      __syncthreads();
    }
    if (pass == 0 && threadIdx.x == 0) total = scan[kThreads - 1];
    __syncthreads();
    const unsigned long long all = total;
    unsigned long long at = below + scan[threadIdx.x] - run;  // the weight before this run
    int found = -1;
    unsigned long long found_at = 0;
    for (int j = 0; j < per && all > 0; ++j) {
      const int b = threadIdx.x * per + j;
      const unsigned long long next = at + sh[b];
      if (2 * at < all && 2 * next >= all) found = b, found_at = at;  // half the weight is reached here
      at = next;
    }
    __syncthreads();  // (every thread has read prefix and below)
    if (found >= 0) {
      prefix = (pass == 0 ? 0u : want << bits) | unsigned(found);
      below = found_at;
    }
    __syncthreads();
  }
  if (blockIdx.x == 0 && threadIdx.x == 0) {
    const float key = KeyFloat(prefix);
    out[0] = double(__ldcg(count));
    out[1] = total > 0 ? exp(double(key)) : 0.0;
    out[2] = total > 0 ? double(key) : 0.0;
  }
  grid.sync();  // every block has read the bins and the count: zero them for the next launch
  for (int i = blockIdx.x * kThreads + threadIdx.x; i < 3 * kMaxBins; i += gridDim.x * kThreads) bins[i] = 0;
  if (blockIdx.x == 0 && threadIdx.x == 0) *count = 0;
}

// The fixed point of the weights (confidences, at most 1): 2^40 a unit, fewer bits where the
// samples' sum (twice it, in the pick) would not fit in 64 bits with room for weights up to 4.
int WeightShift(long n) {
  int log2n = 0;
  while ((1L << log2n) < n) ++log2n;
  return std::min(40, 60 - log2n);
}

// The sample's key and weight as SelectPass reads them: 0 weight where there is no sample.
__device__ void StoreSample(bool valid, float key, float weight, double scale, unsigned* k,
                                   unsigned long long* w) {
  if (valid) {
    *k = OrderedKey(key);
    // (at least one unit: a sample lighter than the fixed point's unit still counts, as on the CPU)
    const unsigned long long fixed = (unsigned long long)(double(weight) * scale);
    *w = fixed > 0 ? fixed : 1;
  } else {
    *k = 0;
    *w = 0;
  }
}
}  // namespace

GpuExposureEstimator::GpuExposureEstimator(int width, int height, const ExposureOptions& o)
    : o_(o), sw_((width + o.stride - 1) / o.stride), sh_((height + o.stride - 1) / o.stride), pose_(1) {
  const std::size_t ns = std::size_t(sw_) * std::size_t(sh_);
  keys_ = DeviceBuffer<unsigned>(ns);
  weights_ = DeviceBuffer<unsigned long long>(ns);
  bins_ = DeviceBuffer<unsigned long long>(3 * kMaxBins);
  state_ = DeviceBuffer<std::uint8_t>(sizeof(unsigned long long));
  out_ = DeviceBuffer<double>(3);
  HDRF_CUDA_CHECK(cudaMemset(bins_.data(), 0, sizeof(unsigned long long) * 3 * kMaxBins));
  HDRF_CUDA_CHECK(cudaMemset(state_.data(), 0, sizeof(unsigned long long)));
  HDRF_CUDA_CHECK(cudaMallocHost(&host_pose_, sizeof(tracking::PoseD)));
  HDRF_CUDA_CHECK(cudaMallocHost(&host_out_, 3 * sizeof(double)));
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

template <typename Make>
void GpuExposureEstimator::QueueSelect(int n, Make make, cudaStream_t stream) {
  // As many blocks as can be resident at once (a cooperative launch needs them all), at most
  // one per kThreads samples.
  static const int resident = [] {
    int per_sm = 0, sms = 0, device = 0;
    HDRF_CUDA_CHECK(cudaGetDevice(&device));
    HDRF_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
    HDRF_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, SelectKernel<Make>, kThreads, 0));
    return std::max(1, per_sm * sms);
  }();
  const int blocks = std::max(1, std::min({kBlocks, resident, (n + kThreads - 1) / kThreads}));
  unsigned* keys = keys_.data();
  unsigned long long *weights = weights_.data(), *bins = bins_.data();
  auto* count = reinterpret_cast<unsigned long long*>(state_.data());
  double* out = out_.data();
  void* args[] = {&n, &make, &keys, &weights, &bins, &count, &out};
  HDRF_CUDA_CHECK(cudaLaunchCooperativeKernel(reinterpret_cast<const void*>(&SelectKernel<Make>), dim3(blocks),
                                              dim3(kThreads), args, 0, stream));
  HDRF_CUDA_CHECK(cudaMemcpyAsync(host_out_, out_.data(), 3 * sizeof(double), cudaMemcpyDeviceToHost, stream));
}

void GpuExposureEstimator::Queue(const ExposureArgs& a, const tracking::PoseD* T_world_live, cudaStream_t stream) {
  const int stride = o_.stride, sw = sw_;
  const double scale = std::ldexp(1.0, WeightShift(long(sw_) * sh_));
  QueueSelect(
      sw_ * sh_,
      [=] __device__(int i, unsigned* k, unsigned long long* w) {
        ExposureArgs b = a;
        b.T_live_world = tracking::ToRigid(tracking::Inverse(*T_world_live));
        float lr = 0.f, wt = 0.f;
        const bool valid = ExposureSample(b, stride * (i % sw), stride * (i / sw), &lr, &wt);
        StoreSample(valid, lr, wt, scale, k, w);
      },
      stream);
}

ExposureEstimate GpuExposureEstimator::Result() const {
  ExposureEstimate e;
  e.samples = long(host_out_[0]);
  if (e.samples < o_.min_samples) return e;
  e.ratio = host_out_[1];
  e.log_ratio = float(host_out_[2]);
  e.valid = true;
  return e;
}

ExposureEstimate GpuWeightedMedianRatio(const std::vector<std::pair<float, float>>& samples, int min_samples) {
  ExposureOptions o;
  o.stride = 1;
  o.min_samples = min_samples;
  const int n = std::max(1, int(samples.size()));
  GpuExposureEstimator est(n, 1, o);
  std::vector<float> k(samples.size()), w(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) k[i] = samples[i].first, w[i] = samples[i].second;
  DeviceBuffer<float> dk(k.size()), dw(w.size());
  if (!k.empty()) {
    HDRF_CUDA_CHECK(cudaMemcpy(dk.data(), k.data(), sizeof(float) * k.size(), cudaMemcpyHostToDevice));
    HDRF_CUDA_CHECK(cudaMemcpy(dw.data(), w.data(), sizeof(float) * w.size(), cudaMemcpyHostToDevice));
  }
  const float *kp = dk.data(), *wp = dw.data();
  const double scale = std::ldexp(1.0, WeightShift(n));
  const int count = int(samples.size());
  est.QueueSelect(
      n,
      [=] __device__(int i, unsigned* key, unsigned long long* weight) {
        StoreSample(i < count, i < count ? kp[i] : 0.f, i < count ? wp[i] : 0.f, scale, key, weight);
      },
      nullptr);
  HDRF_CUDA_CHECK(cudaStreamSynchronize(nullptr));
  return est.Result();
}

}  // namespace hdrf::exposure
