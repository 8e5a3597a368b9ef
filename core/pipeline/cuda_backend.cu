// The CUDA backend: every per-pixel and per-voxel stage of the engine as kernels over the
// shared per-element functions (imaging_impl.h, tracking_impl.h, volume_impl.h), with the
// frame's images and the model resident on the GPU. Per frame the host sends the colour and
// depth, and reads back the Gauss-Newton systems (33 doubles per iteration), the exposure
// estimate and the count of new bricks; nothing else crosses the bus.
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/cuda_check.h"
#include "common/device_buffer.h"
#include "imaging/imaging_impl.h"
#include "mesh/mesh_impl.h"
#include "pipeline/backend.h"
#include "pipeline/pipeline.h"
#include "tracking/tracking_impl.h"
#include "volume/volume_impl.h"

namespace hdrf::pipeline::cuda_detail {

constexpr int kReduceThreads = 256;
constexpr int kReduceBlocks = 264;

template <typename F>
__global__ void PixelKernel(int w, int h, F f) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x < w && y < h) f(x, y);
}
template <typename F>
void ForEachPixel(int w, int h, F f) {
  if (w <= 0 || h <= 0) return;
  const dim3 block(32, 8), grid((w + 31) / 32, (h + 7) / 8);
  PixelKernel<<<grid, block>>>(w, h, f);
  HDRF_CUDA_CHECK_LAUNCH();
}
// Row pass of the NR integral images: one block per row stages the row in shared memory
// (coalesced), one thread runs the same sequential sums as the CPU, all threads write back.
__global__ void NrRowPassKernel(ImageView<const float> cells, imaging::NrIntegrals in) {
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
    const imaging::NrIntegrals local{{c, sw + 1, 2}, {a, sw + 1, 2}, {b, sw + 1, 2}};
    imaging::NrRowPass(row, local, 0);  // writes entries (x, 1) of the 2-row local images
  }
  __syncthreads();
  for (int x = threadIdx.x; x <= sw; x += blockDim.x) {
    in.cnt(x, y + 1) = c[sw + 1 + x];
    in.s1(x, y + 1) = a[sw + 1 + x];
    in.s2(x, y + 1) = b[sw + 1 + x];
  }
}

template <typename F>
__global__ void IndexKernel(int n, F f) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) f(i);
}
template <typename F>
void ForEachIndex(int n, F f) {
  if (n <= 0) return;
  IndexKernel<<<(n + 255) / 256, 256>>>(n, f);
  HDRF_CUDA_CHECK_LAUNCH();
}

// Block-level reduction of per-pixel sums of K doubles: each thread sums its pixels, warps
// reduce by shuffles, the block writes one partial; a second kernel adds the partials in a
// fixed order (deterministic, no atomics).
template <typename Acc, typename F>
__global__ void __launch_bounds__(kReduceThreads)
    SumKernel(int w, int h, F f, double* partial, unsigned* done, double* out) {
  constexpr int K = sizeof(Acc::v) / sizeof(double);
  Acc acc;
  const int n = w * h;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) f(i % w, i / w, acc);
  __shared__ double sh[kReduceThreads / 32][K];
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
    for (int wi = 0; wi < kReduceThreads / 32; ++wi) s += sh[wi][threadIdx.x];
    partial[blockIdx.x * K + threadIdx.x] = s;
  }
  // The last block to finish adds the partials, in block order (the same sum every run).
  __shared__ bool last;
  __threadfence();
  __syncthreads();
  if (threadIdx.x == 0) last = atomicAdd(done, 1u) == gridDim.x - 1;
  __syncthreads();
  if (!last) return;
  __threadfence();
  if (threadIdx.x < K) {
    double s = 0;
    for (int b = 0; b < int(gridDim.x); ++b) s += static_cast<volatile double*>(partial)[b * K + threadIdx.x];
    out[threadIdx.x] = s;
  }
  if (threadIdx.x == 0) *done = 0;  // ready for the next reduction
}

struct Count1 {
  double v[1] = {0};
};

struct LiveLevelD {
  PinholeCamera cam;
  DeviceImage<float> depth, intensity, gx, gy, weight;
  DeviceImage<Float3> vertex, normal;
  tracking::LiveView view() const {
    return {cam, vertex.view(), normal.view(), intensity.view(), gx.view(), gy.view(), weight.view()};
  }
};
struct RefLevelD {
  PinholeCamera cam;
  DeviceImage<Float3> vertex, normal;
  DeviceImage<float> intensity;
  tracking::ReferenceView view() const { return {cam, vertex.view(), normal.view(), intensity.view()}; }
};
struct RenderD {
  DeviceImage<Float3> vertex, normal, radiance;
  DeviceImage<float> nr, depth;
  RenderD() = default;
  RenderD(int w, int h) : vertex(w, h), normal(w, h), radiance(w, h), nr(w, h), depth(w, h) {}
};
struct BrickCoord {
  int x, y, z;
};

template <typename T>
void CopyD2D(DeviceImage<T>& dst, const DeviceImage<T>& src) {
  HDRF_CUDA_CHECK(cudaMemcpy(dst.data(), src.data(), sizeof(T) * std::size_t(src.width()) * src.height(),
                             cudaMemcpyDeviceToDevice));
}

class CudaBackend final : public Backend {
 public:
  explicit CudaBackend(const BackendSetup& s);
  ~CudaBackend() override { cudaFreeHost(host_sums_); }
  CudaBackend(const CudaBackend&) = delete;
  CudaBackend& operator=(const CudaBackend&) = delete;
  void Convert(const ColorImage& color, const DepthImage& depth_m) override;
  void Normalize(const ColorImage& color) override;
  void BuildLive() override;
  tracking::GnSystem Accumulate(int level, const Pose& T_world_ref, const Pose& T_world_live) override;
  long LiveValid() override;
  long ReferenceValid() override;
  tracking::ExposureEstimate EstimateExposure(const Pose& T_world_live) override;
  void Integrate(const Pose& T_world_camera, float ratio) override;
  std::size_t AllocatedBricks() override { return allocated_; }
  std::size_t LastVisibleBricks() override {
    int n = 0;
    HDRF_CUDA_CHECK(cudaMemcpy(&n, counts_.data() + 1, sizeof(int), cudaMemcpyDeviceToHost));
    return std::size_t(n);
  }
  std::size_t VolumeBytes() override {
    return index_.size() * sizeof(int) + std::size_t(allocated_) * 512 * std::size_t(vbytes_);
  }
  void Raycast(const Pose& T_world_camera) override;
  void ReferenceFromRender() override;
  void ReferenceFromLive(const Pose& T_world_camera) override;
  void Synchronize() override { cuda::Synchronize(); }
  volume::Volume::Rendering Render(const Pose& T_world_camera) override;
  const volume::Volume& HostVolume() override;
  mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress) override;
  template <typename V>
  mesh::Mesh ExtractMeshT();
  FrameImages Download() override;

  // Helpers (public: CUDA extended lambdas may not live in private members).
  void BuildReferencePyramid();
  void RaycastInto(RenderD& out, const Pose& T);
  void Grow(int bricks);
  template <typename V>
  volume::VolumeView<V> DeviceView() const;
  template <typename V>
  void FillDefault(long first, long count);
  template <typename V>
  void IntegrateBricks(const volume::IntegrateArgs& a);
  template <typename V>
  void RaycastT(RenderD& out, const Pose& T);
  void NormalizeLum(ImageView<const float> lum, ImageView<float> nr);
  void RowPass(ImageView<const float> cells, const imaging::NrIntegrals& in);
  template <typename Acc, typename F>
  Acc Sum(int w, int h, F f);

 private:
  const PipelineOptions& o_;
  PinholeCamera cam_;
  imaging::BilateralTables bilateral_;
  DeviceBuffer<float> inverse_, pcf_;
  DeviceImage<Rgb8> color_;
  DeviceImage<float> depth_raw_, depth_, conf_, maxconf_, lum_, nr_, lum_render_;
  DeviceImage<Float3> radiance_;
  // Normalized radiance on the down-sampled grid.
  DeviceImage<float> cells_, mean_s_, std_s_;
  DeviceImage<double> cnt_, s1_, s2_;
  std::vector<LiveLevelD> live_;
  std::vector<RefLevelD> ref_;
  RenderD render_;
  // Reductions.
  DeviceBuffer<double> partial_, sums_;
  DeviceBuffer<unsigned> done_;
  double* host_sums_ = nullptr;  // pinned
  // Exposure estimate.
  DeviceBuffer<float> keys_, vals_, keys_sorted_, vals_sorted_;
  DeviceBuffer<double> cum_;
  DeviceBuffer<std::uint8_t> temp_;
  DeviceBuffer<double> exposure_out_;  // (count, ratio)
  // The model.
  volume::Volume mirror_;  // geometry, limits; host copy on request
  bool mirror_fresh_ = true;
  DeviceBuffer<int> index_, flags_, scan_, todo_;
  DeviceBuffer<std::uint8_t> coarse_, visible_;
  DeviceBuffer<std::uint8_t> pool_;  // 512 encoded voxels per brick
  int vbytes_ = 0;
  DeviceBuffer<BrickCoord> coords_;
  DeviceBuffer<int> counts_;  // (new bricks, todo bricks)
  int allocated_ = 0, capacity_ = 0;
  bool full_ = false;
};

CudaBackend::CudaBackend(const BackendSetup& s)
    : o_(*s.options), cam_(s.camera), bilateral_(imaging::MakeBilateralTables(2.0f, 0.03f, 3)),
      mirror_(s.options->volume) {
  const int w = cam_.width, h = cam_.height;
  inverse_.Upload(s.inverse, 768);
  pcf_.Upload(s.pcf, 768);
  color_ = DeviceImage<Rgb8>(w, h);
  depth_raw_ = DeviceImage<float>(w, h);
  depth_ = DeviceImage<float>(w, h);
  conf_ = DeviceImage<float>(w, h);
  maxconf_ = DeviceImage<float>(w, h);
  lum_ = DeviceImage<float>(w, h);
  nr_ = DeviceImage<float>(w, h);
  radiance_ = DeviceImage<Float3>(w, h);
  const int f = o_.nr.downsample, sw = (w + f - 1) / f, sh = (h + f - 1) / f;
  cells_ = DeviceImage<float>(sw, sh);
  mean_s_ = DeviceImage<float>(sw, sh);
  std_s_ = DeviceImage<float>(sw, sh);
  cnt_ = DeviceImage<double>(sw + 1, sh + 1);
  s1_ = DeviceImage<double>(sw + 1, sh + 1);
  s2_ = DeviceImage<double>(sw + 1, sh + 1);
  PinholeCamera c = cam_;
  for (int l = 0; l < o_.tracker.levels; ++l) {
    LiveLevelD L;
    L.cam = c;
    L.depth = DeviceImage<float>(c.width, c.height);
    L.intensity = DeviceImage<float>(c.width, c.height);
    L.gx = DeviceImage<float>(c.width, c.height);
    L.gy = DeviceImage<float>(c.width, c.height);
    L.weight = DeviceImage<float>(c.width, c.height);
    L.vertex = DeviceImage<Float3>(c.width, c.height);
    L.normal = DeviceImage<Float3>(c.width, c.height);
    live_.push_back(std::move(L));
    RefLevelD R;
    R.cam = c;
    R.vertex = DeviceImage<Float3>(c.width, c.height);
    R.normal = DeviceImage<Float3>(c.width, c.height);
    R.intensity = DeviceImage<float>(c.width, c.height);
    ref_.push_back(std::move(R));
    c = c.Scaled(2);
  }
  render_ = RenderD(w, h);
  partial_ = DeviceBuffer<double>(std::size_t(kReduceBlocks) * tracking::GnSystem::kSize);
  sums_ = DeviceBuffer<double>(tracking::GnSystem::kSize);
  done_ = DeviceBuffer<unsigned>(1);
  HDRF_CUDA_CHECK(cudaMemset(done_.data(), 0, sizeof(unsigned)));
  HDRF_CUDA_CHECK(cudaMallocHost(&host_sums_, sizeof(double) * tracking::GnSystem::kSize));
  const std::size_t ns = std::size_t((w + 1) / 2) * std::size_t((h + 1) / 2);
  keys_ = DeviceBuffer<float>(ns);
  vals_ = DeviceBuffer<float>(ns);
  keys_sorted_ = DeviceBuffer<float>(ns);
  vals_sorted_ = DeviceBuffer<float>(ns);
  cum_ = DeviceBuffer<double>(ns);
  exposure_out_ = DeviceBuffer<double>(2);
  const int nb = mirror_.bricks_per_side();
  const std::size_t nb3 = std::size_t(nb) * nb * nb;
  index_ = DeviceBuffer<int>(nb3);
  HDRF_CUDA_CHECK(cudaMemset(index_.data(), 0xff, nb3 * sizeof(int)));  // -1
  flags_ = DeviceBuffer<int>(nb3);
  scan_ = DeviceBuffer<int>(nb3);
  todo_ = DeviceBuffer<int>(nb3);
  visible_ = DeviceBuffer<std::uint8_t>(nb3);
  const int nc = (nb + 3) / 4;
  coarse_ = DeviceBuffer<std::uint8_t>(std::size_t(nc) * nc * nc);
  HDRF_CUDA_CHECK(cudaMemset(coarse_.data(), 0, coarse_.size()));
  counts_ = DeviceBuffer<int>(2);
  HDRF_CUDA_CHECK(cudaMemset(counts_.data(), 0, 2 * sizeof(int)));
  // Scratch for the scans and the sort, sized for the larger of the two.
  std::size_t scan_bytes = 0, sort_bytes = 0, cum_bytes = 0;
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, scan_bytes, flags_.data(), scan_.data(), int(nb3)));
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, sort_bytes, keys_.data(), keys_sorted_.data(),
                                                  vals_.data(), vals_sorted_.data(), int(ns)));
  HDRF_CUDA_CHECK(cub::DeviceScan::InclusiveSum(nullptr, cum_bytes, cum_.data(), cum_.data(), int(ns)));
  vbytes_ = volume::EncodingBytes(o_.volume.encoding);
  lum_render_ = DeviceImage<float>(w, h);
  temp_ = DeviceBuffer<std::uint8_t>(std::max({scan_bytes, sort_bytes, cum_bytes, std::size_t(16)}));
  Grow(4096);
}

template <typename V>
volume::VolumeView<V> CudaBackend::DeviceView() const {
  volume::VolumeView<V> v = mirror_.view<V>();  // geometry from the host twin
  v.index = index_.data();
  v.coarse = coarse_.data();
  v.pool = reinterpret_cast<V*>(const_cast<std::uint8_t*>(pool_.data()));
  return v;
}

template <typename V>
void CudaBackend::FillDefault(long first, long count) {
  V* p = reinterpret_cast<V*>(pool_.data());
  ForEachIndex(int(count), [=] __device__(int i) { p[first + i] = V{}; });
}

void CudaBackend::Grow(int want) {
  const int max_bricks = int(std::min<std::size_t>(mirror_.max_bricks(), 1u << 30));
  const int cap = std::min(max_bricks, std::max(want, capacity_ * 2));
  if (cap <= capacity_) return;
  DeviceBuffer<std::uint8_t> pool{std::size_t(cap) * 512 * std::size_t(vbytes_)};
  DeviceBuffer<BrickCoord> coords{std::size_t(cap)};
  if (allocated_ > 0) {
    HDRF_CUDA_CHECK(cudaMemcpy(pool.data(), pool_.data(), std::size_t(allocated_) * 512 * std::size_t(vbytes_),
                               cudaMemcpyDeviceToDevice));
    HDRF_CUDA_CHECK(cudaMemcpy(coords.data(), coords_.data(), std::size_t(allocated_) * sizeof(BrickCoord),
                               cudaMemcpyDeviceToDevice));
  }
  pool_ = std::move(pool);
  coords_ = std::move(coords);
  const long first = long(capacity_) * 512, count = long(cap) * 512 - first;
  switch (o_.volume.encoding) {
    case volume::VoxelEncoding::kNoNr: FillDefault<volume::NoNrVoxel>(first, count); break;
    case volume::VoxelEncoding::kCompact: FillDefault<volume::CompactVoxel>(first, count); break;
    default: FillDefault<volume::FullVoxel>(first, count);
  }
  capacity_ = cap;
}

template <typename Acc, typename F>
Acc CudaBackend::Sum(int w, int h, F f) {
  constexpr int K = sizeof(Acc::v) / sizeof(double);
  const int blocks = std::max(1, std::min(kReduceBlocks, (w * h + kReduceThreads - 1) / kReduceThreads));
  SumKernel<Acc><<<blocks, kReduceThreads>>>(w, h, f, partial_.data(), done_.data(), sums_.data());
  HDRF_CUDA_CHECK_LAUNCH();
  HDRF_CUDA_CHECK(cudaMemcpyAsync(host_sums_, sums_.data(), sizeof(double) * K, cudaMemcpyDeviceToHost, 0));
  HDRF_CUDA_CHECK(cudaStreamSynchronize(0));
  Acc out;
  for (int k = 0; k < K; ++k) out.v[k] = host_sums_[k];
  return out;
}

void CudaBackend::Convert(const ColorImage& color, const DepthImage& depth_m) {
  const int w = cam_.width, h = cam_.height;
  cuda::CopyHostToDevice(color_.data(), color.data(), color.size() * sizeof(Rgb8));
  cuda::CopyHostToDevice(depth_raw_.data(), depth_m.data(), depth_m.size() * sizeof(float));
  const auto c = color_.view();
  const float *inv = inverse_.data(), *pcf = pcf_.data();
  const auto rad = radiance_.view();
  const auto conf = conf_.view(), mx = maxconf_.view();
  ForEachPixel(w, h, [=] __device__(int x, int y) {
    imaging::ConvertPixel(c(x, y), inv, pcf, &rad(x, y), &conf(x, y), &mx(x, y));
  });
  const ImageView<const float> raw = depth_raw_.view();
  const auto out = depth_.view();
  if (o_.bilateral) {
    const imaging::BilateralTables t = bilateral_;
    ForEachPixel(w, h, [=] __device__(int x, int y) { out(x, y) = imaging::BilateralPixel(raw, t, x, y); });
  } else {
    CopyD2D(depth_, depth_raw_);
  }
}

void CudaBackend::RowPass(ImageView<const float> cells, const imaging::NrIntegrals& in) {
  const int sw = cells.width;
  const std::size_t shared = 3 * 2 * std::size_t(sw + 1) * sizeof(double) + std::size_t(sw) * sizeof(float);
  if (shared <= 48 * 1024) {
    NrRowPassKernel<<<cells.height, 128, shared>>>(cells, in);
    HDRF_CUDA_CHECK_LAUNCH();
  } else {  // very wide images: one thread per row
    ForEachIndex(cells.height, [=] __device__(int y) { imaging::NrRowPass(cells, in, y); });
  }
}

void CudaBackend::NormalizeLum(ImageView<const float> lumc, ImageView<float> nr) {
  const int w = lumc.width, h = lumc.height, f = o_.nr.downsample;
  const auto cells = cells_.view();
  ForEachPixel(cells.width, cells.height,
               [=] __device__(int x, int y) { cells(x, y) = imaging::NrCellMean(lumc, x, y, f); });
  const imaging::NrIntegrals in{cnt_.view(), s1_.view(), s2_.view()};
  const ImageView<const float> cellc = cells;
  RowPass(cellc, in);
  ForEachIndex(cells.width + 1, [=] __device__(int x) { imaging::NrColumnPass(in, x); });
  const auto ms = mean_s_.view(), ss = std_s_.view();
  const int r = o_.nr.patch / 2;
  ForEachPixel(cells.width, cells.height,
               [=] __device__(int x, int y) { imaging::NrLocalStats(in, x, y, r, &ms(x, y), &ss(x, y)); });
  const float min_std = o_.nr.min_std;
  const ImageView<const float> msc = ms, ssc = ss;
  ForEachPixel(w, h, [=] __device__(int x, int y) {
    imaging::NrPixel(lumc, msc, ssc, f, min_std, x, y, &nr(x, y), nullptr, nullptr);
  });
}

void CudaBackend::Normalize(const ColorImage&) {
  const int w = cam_.width, h = cam_.height;
  const auto rad = radiance_.view();
  const auto lum = lum_.view();
  ForEachPixel(w, h, [=] __device__(int x, int y) { lum(x, y) = Luminance(rad(x, y)); });
  NormalizeLum(lum, nr_.view());
  LiveLevelD& L0 = live_[0];
  if (o_.tracker.kind == tracking::TrackerKind::kIntensity) {
    const ImageView<const Rgb8> c = color_.view();
    const auto ti = L0.intensity.view(), tw = L0.weight.view();
    ForEachPixel(w, h, [=] __device__(int x, int y) {
      ti(x, y) = imaging::RawIntensityPixel(c(x, y));
      tw(x, y) = 1.f;
    });
  } else {
    CopyD2D(L0.intensity, nr_);
    CopyD2D(L0.weight, conf_);
  }
}

void CudaBackend::BuildLive() {
  CopyD2D(live_[0].depth, depth_);
  for (std::size_t l = 0; l < live_.size(); ++l) {
    LiveLevelD& L = live_[l];
    const int w = L.cam.width, h = L.cam.height;
    if (l > 0) {
      const LiveLevelD& P = live_[l - 1];
      const ImageView<const float> pd = P.depth.view(), pi = P.intensity.view(), pw = P.weight.view();
      const ImageView<float> d = L.depth.view(), in = L.intensity.view(), wt = L.weight.view();
      ForEachPixel(w, h, [=] __device__(int x, int y) {
        d(x, y) = imaging::DownsampleDepthPixel(pd, x, y);
        in(x, y) = imaging::Mean2x2(pi, x, y);
        wt(x, y) = imaging::Mean2x2(pw, x, y);
      });
    }
    const ImageView<const float> d = L.depth.view(), in = L.intensity.view();
    const auto v = L.vertex.view();
    const auto gx = L.gx.view(), gy = L.gy.view();
    const PinholeCamera cam = L.cam;
    ForEachPixel(w, h, [=] __device__(int x, int y) {
      v(x, y) = imaging::VertexPixel(d, cam, x, y);
      gx(x, y) = imaging::GradXPixel(in, x, y);
      gy(x, y) = imaging::GradYPixel(in, x, y);
    });
    const ImageView<const Float3> vc = v;
    const auto n = L.normal.view();
    ForEachPixel(w, h, [=] __device__(int x, int y) { n(x, y) = imaging::NormalPixel(vc, 0.1f, x, y); });
  }
}

tracking::GnSystem CudaBackend::Accumulate(int level, const Pose& T_world_ref, const Pose& T_world_live) {
  const bool use_icp = o_.tracker.kind == tracking::TrackerKind::kIcp || o_.tracker.kind == tracking::TrackerKind::kNrIcp;
  const bool use_photo = o_.tracker.kind != tracking::TrackerKind::kIcp;
  const tracking::ReferenceView ref = ref_[std::size_t(level)].view();
  const tracking::LiveView live = live_[std::size_t(level)].view();
  const tracking::IcpArgs ia = tracking::MakeIcpArgs(ref, T_world_ref, live, T_world_live, o_.tracker);
  const tracking::PhotoArgs pa = tracking::MakePhotoArgs(ref, live, T_world_live, o_.tracker);
  // Live and reference levels have the same size: one pass adds both terms of a pixel.
  return Sum<tracking::GnSystem>(live.cam.width, live.cam.height,
                                 [=] __device__(int x, int y, tracking::GnSystem& acc) {
                                   if (use_icp) tracking::IcpTerm(ia, x, y, acc);
                                   if (use_photo) tracking::PhotoTerm(pa, x, y, acc);
                                 });
}

long CudaBackend::LiveValid() {
  const ImageView<const Float3> v = live_[0].vertex.view();
  const Count1 c = Sum<Count1>(v.width, v.height, [=] __device__(int x, int y, Count1& acc) {
    acc.v[0] += v(x, y).z > 0.f ? 1.0 : 0.0;
  });
  return long(c.v[0]);
}

long CudaBackend::ReferenceValid() {
  const ImageView<const Float3> v = ref_[0].vertex.view();
  const Count1 c = Sum<Count1>(v.width, v.height, [=] __device__(int x, int y, Count1& acc) {
    const Float3 p = v(x, y);
    acc.v[0] += (p.x != 0.f || p.y != 0.f || p.z != 0.f) ? 1.0 : 0.0;
  });
  return long(c.v[0]);
}

tracking::ExposureEstimate CudaBackend::EstimateExposure(const Pose& T) {
  const tracking::ExposureArgs a{render_.vertex.view(), render_.radiance.view(), radiance_.view(),
                                 conf_.view(), cam_, ToRigidTransform(T.inverse())};
  const int sw = (cam_.width + 1) / 2, sh = (cam_.height + 1) / 2, n = sw * sh;
  float *keys = keys_.data(), *vals = vals_.data();
  ForEachPixel(sw, sh, [=] __device__(int x, int y) {
    float lr, wt;
    const int i = y * sw + x;
    if (tracking::ExposureSample(a, 2 * x, 2 * y, &lr, &wt)) {
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
  ForEachIndex(n, [=] __device__(int i) { cum[i] = vs[i]; });
  bytes = temp_.size();
  HDRF_CUDA_CHECK(cub::DeviceScan::InclusiveSum(temp_.data(), bytes, cum, cum, n));
  double* out = exposure_out_.data();
  HDRF_CUDA_CHECK(cudaMemset(out, 0, 2 * sizeof(double)));
  // Valid samples are the finite keys at the front; the median is the first sample whose
  // cumulative weight reaches half of the total.
  ForEachIndex(n, [=] __device__(int i) {
    if (isfinite(ks[i]) && (i + 1 == n || !isfinite(ks[i + 1]))) out[0] = double(i + 1);
  });
  ForEachIndex(n, [=] __device__(int i) {
    const int count = int(out[0]);
    if (i >= count) return;
    const double half = 0.5 * cum[count - 1];
    if (cum[i] >= half && (i == 0 || cum[i - 1] < half)) out[1] = exp(double(ks[i]));
  });
  double host[2];
  HDRF_CUDA_CHECK(cudaMemcpy(host, out, sizeof(host), cudaMemcpyDeviceToHost));
  tracking::ExposureEstimate e;
  e.samples = long(host[0]);
  if (e.samples < 50) return e;
  e.ratio = host[1];
  e.valid = true;
  return e;
}

void CudaBackend::Integrate(const Pose& T, float ratio) {
  const int nb = mirror_.bricks_per_side(), nb3 = nb * nb * nb;
  volume::IntegrateArgs a =
      volume::Volume::MakeIntegrateArgs(o_.volume, mirror_.origin(), cam_, T, ratio);
  a.depth = depth_.view();
  a.normals = live_[0].normal.view();
  a.radiance = radiance_.view();
  a.nr = nr_.view();
  a.confidence = conf_.view();
  a.max_confidence = maxconf_.view();
  // 1. Bricks in the truncation band of every second depth pixel.
  std::uint8_t* vis = visible_.data();
  HDRF_CUDA_CHECK(cudaMemset(vis, 0, std::size_t(nb3)));
  const RigidTransform Twc = ToRigidTransform(T);
  const int bw = nb;
  ForEachPixel((cam_.width + 1) / 2, (cam_.height + 1) / 2, [=] __device__(int x, int y) {
    volume::ForBricksAlongRay(a, Twc, bw, 2 * x, 2 * y,
                              [&](int bx, int by, int bz) { vis[(bz * bw + by) * bw + bx] = 1; });
  });
  // 2. New bricks take pool slots in brick-index order (as on the CPU), up to the limit.
  int* index = index_.data();
  int* flags = flags_.data();
  ForEachIndex(nb3, [=] __device__(int i) { flags[i] = vis[i] && index[i] < 0 ? 1 : 0; });
  std::size_t bytes = temp_.size();
  int* pos = scan_.data();
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp_.data(), bytes, flags, pos, nb3));
  int last[2];
  HDRF_CUDA_CHECK(cudaMemcpy(&last[0], pos + nb3 - 1, sizeof(int), cudaMemcpyDeviceToHost));
  HDRF_CUDA_CHECK(cudaMemcpy(&last[1], flags + nb3 - 1, sizeof(int), cudaMemcpyDeviceToHost));
  const int wanted = last[0] + last[1];
  const int max_bricks = int(std::min<std::size_t>(mirror_.max_bricks(), 1u << 30));
  const int allowed = std::min(wanted, max_bricks - allocated_);
  if (allowed < wanted) full_ = true;
  if (allocated_ + allowed > capacity_) Grow(allocated_ + allowed);
  if (allowed > 0) {
    BrickCoord* coords = coords_.data();
    std::uint8_t* coarse = coarse_.data();
    const int base = allocated_, nc = (nb + 3) / 4;
    ForEachIndex(nb3, [=] __device__(int i) {
      if (!flags[i] || pos[i] >= allowed) return;
      const int slot = base + pos[i];
      const int bx = i % bw, by = (i / bw) % bw, bz = i / (bw * bw);
      index[i] = slot;
      coords[slot] = {bx, by, bz};
      coarse[((bz >> 2) * nc + (by >> 2)) * nc + (bx >> 2)] = 1;
    });
    allocated_ += allowed;
  }
  // 3. The allocated visible bricks, compacted; one block of 512 threads per brick.
  ForEachIndex(nb3, [=] __device__(int i) { flags[i] = vis[i] && index[i] >= 0 ? 1 : 0; });
  bytes = temp_.size();
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp_.data(), bytes, flags, pos, nb3));
  int* todo = todo_.data();
  int* counts = counts_.data();
  ForEachIndex(nb3, [=] __device__(int i) {
    if (flags[i]) todo[pos[i]] = index[i];
    if (i == nb3 - 1) counts[1] = pos[i] + flags[i];
  });
  switch (o_.volume.encoding) {
    case volume::VoxelEncoding::kNoNr: IntegrateBricks<volume::NoNrVoxel>(a); break;
    case volume::VoxelEncoding::kCompact: IntegrateBricks<volume::CompactVoxel>(a); break;
    default: IntegrateBricks<volume::FullVoxel>(a);
  }
  mirror_fresh_ = false;
}

template <typename V>
void CudaBackend::IntegrateBricks(const volume::IntegrateArgs& a) {
  V* pool = reinterpret_cast<V*>(pool_.data());
  const BrickCoord* coords = coords_.data();
  const int* todo = todo_.data();
  const int* counts = counts_.data();
  IndexKernel<<<1024, 512>>>(1024 * 512, [=] __device__(int) {
    const int n_todo = counts[1];
    for (int k = blockIdx.x; k < n_todo; k += gridDim.x) {
      const int slot = todo[k];
      const BrickCoord bc = coords[slot];
      volume::IntegrateVoxel(a, bc.x, bc.y, bc.z, threadIdx.x, pool[long(slot) * 512 + threadIdx.x]);
    }
  });
  HDRF_CUDA_CHECK_LAUNCH();
}

void CudaBackend::RaycastInto(RenderD& out, const Pose& T) {
  switch (o_.volume.encoding) {
    case volume::VoxelEncoding::kNoNr: RaycastT<volume::NoNrVoxel>(out, T); break;
    case volume::VoxelEncoding::kCompact: RaycastT<volume::CompactVoxel>(out, T); break;
    default: RaycastT<volume::FullVoxel>(out, T);
  }
  if (!volume::EncodingStoresNr(o_.volume.encoding)) {
    // The model keeps no NR: normalize the ray-cast radiance instead.
    const auto rad = out.radiance.view();
    const auto lum = lum_render_.view();
    ForEachPixel(cam_.width, cam_.height, [=] __device__(int x, int y) { lum(x, y) = Luminance(rad(x, y)); });
    NormalizeLum(lum, out.nr.view());
  }
}

template <typename Enc>
void CudaBackend::RaycastT(RenderD& out, const Pose& T) {
  const volume::VolumeView<Enc> V = DeviceView<Enc>();
  const volume::RaycastArgs a{cam_, ToRigidTransform(T), 0.2f, 8.0f};
  const auto v = out.vertex.view(), n = out.normal.view(), r = out.radiance.view();
  const auto nr = out.nr.view(), d = out.depth.view();
  ForEachPixel(cam_.width, cam_.height, [=] __device__(int x, int y) {
    const volume::RayHit hit = volume::RaycastPixel(V, a, x, y);
    v(x, y) = hit.vertex;
    n(x, y) = hit.normal;
    r(x, y) = hit.radiance;
    nr(x, y) = hit.nr;
    d(x, y) = hit.depth;
  });
}

void CudaBackend::Raycast(const Pose& T) { RaycastInto(render_, T); }

void CudaBackend::BuildReferencePyramid() {
  for (std::size_t l = 1; l < ref_.size(); ++l) {
    const RefLevelD& P = ref_[l - 1];
    RefLevelD& L = ref_[l];
    const ImageView<const Float3> pv = P.vertex.view(), pn = P.normal.view();
    const ImageView<const float> pi = P.intensity.view();
    const auto v = L.vertex.view(), n = L.normal.view();
    const auto in = L.intensity.view();
    ForEachPixel(L.cam.width, L.cam.height, [=] __device__(int x, int y) {
      v(x, y) = pv(2 * x, 2 * y);
      n(x, y) = pn(2 * x, 2 * y);
      in(x, y) = imaging::Mean2x2(pi, x, y);
    });
  }
}

void CudaBackend::ReferenceFromRender() {
  CopyD2D(ref_[0].vertex, render_.vertex);
  CopyD2D(ref_[0].normal, render_.normal);
  CopyD2D(ref_[0].intensity, render_.nr);
  BuildReferencePyramid();
}

void CudaBackend::ReferenceFromLive(const Pose& T_pose) {
  const RigidTransform T = ToRigidTransform(T_pose);
  const LiveLevelD& L0 = live_[0];
  const ImageView<const Float3> lv = L0.vertex.view(), ln = L0.normal.view();
  const auto v = ref_[0].vertex.view(), n = ref_[0].normal.view();
  ForEachPixel(cam_.width, cam_.height, [=] __device__(int x, int y) {
    const bool ok = lv(x, y).z > 0.f && Length(ln(x, y)) > 0.f;
    v(x, y) = ok ? T.Apply(lv(x, y)) : Float3{0, 0, 0};
    n(x, y) = ok ? T.Rotate(ln(x, y)) : Float3{0, 0, 0};
  });
  CopyD2D(ref_[0].intensity, L0.intensity);
  BuildReferencePyramid();
}

volume::Volume::Rendering CudaBackend::Render(const Pose& T) {
  RenderD tmp(cam_.width, cam_.height);
  RaycastInto(tmp, T);
  volume::Volume::Rendering r;
  r.vertex = tmp.vertex.ToHost();
  r.normal = tmp.normal.ToHost();
  r.radiance = tmp.radiance.ToHost();
  r.nr = tmp.nr.ToHost();
  r.depth = tmp.depth.ToHost();
  return r;
}

FrameImages CudaBackend::Download() {
  FrameImages f;
  f.radiance = radiance_.ToHost();
  f.confidence = conf_.ToHost();
  f.max_confidence = maxconf_.ToHost();
  f.nr = nr_.ToHost();
  f.depth = depth_.ToHost();
  for (const auto& L : live_) {
    f.live_vertex.push_back(L.vertex.ToHost());
    f.live_normal.push_back(L.normal.ToHost());
    f.live_intensity.push_back(L.intensity.ToHost());
    f.live_weight.push_back(L.weight.ToHost());
    f.live_grad_x.push_back(L.gx.ToHost());
  }
  for (const auto& L : ref_) {
    f.ref_vertex.push_back(L.vertex.ToHost());
    f.ref_normal.push_back(L.normal.ToHost());
    f.ref_intensity.push_back(L.intensity.ToHost());
  }
  f.render = {render_.vertex.ToHost(), render_.normal.ToHost(), render_.radiance.ToHost(), render_.nr.ToHost(),
              render_.depth.ToHost()};
  return f;
}

mesh::Mesh CudaBackend::ExtractMesh(const std::function<bool(double)>& progress) {
  // On the GPU the extraction takes milliseconds: progress at its start and end only.
  if (progress && !progress(0.0)) throw Cancelled();
  mesh::Mesh m;
  switch (o_.volume.encoding) {
    case volume::VoxelEncoding::kNoNr: m = ExtractMeshT<volume::NoNrVoxel>(); break;
    case volume::VoxelEncoding::kCompact: m = ExtractMeshT<volume::CompactVoxel>(); break;
    default: m = ExtractMeshT<volume::FullVoxel>();
  }
  if (progress && !progress(1.0)) throw Cancelled();
  return m;
}

template <typename V>
mesh::Mesh CudaBackend::ExtractMeshT() {
  mesh::Mesh m;
  const int cubes = allocated_ * 512;
  if (cubes == 0) return m;
  const volume::VolumeView<V> view = DeviceView<V>();
  const BrickCoord* coords = coords_.data();
  // 1. Triangles per cube, their offsets, then the triangles as edge keys in cube order.
  DeviceBuffer<int> count{static_cast<std::size_t>(cubes) + 1}, offset{static_cast<std::size_t>(cubes) + 1};
  int* cnt = count.data();
  ForEachIndex(cubes + 1, [=] __device__(int c) {
    if (c == cubes) {
      cnt[c] = 0;
      return;
    }
    const BrickCoord b = coords[c / 512];
    const int i = c % 512;
    std::uint64_t t[mesh::kMaxCubeTriangles][3];
    cnt[c] = mesh::CubeTriangles(view, b.x * 8 + (i & 7), b.y * 8 + ((i >> 3) & 7), b.z * 8 + (i >> 6), t);
  });
  std::size_t bytes = 0;
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, cnt, offset.data(), cubes + 1));
  DeviceBuffer<std::uint8_t> temp{std::max<std::size_t>(bytes, 16)};
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), bytes, cnt, offset.data(), cubes + 1));
  int n_tri = 0;
  HDRF_CUDA_CHECK(cudaMemcpy(&n_tri, offset.data() + cubes, sizeof(int), cudaMemcpyDeviceToHost));
  if (n_tri == 0) return m;
  const int n_keys = 3 * n_tri;
  DeviceBuffer<std::uint64_t> tri_keys{static_cast<std::size_t>(n_keys)}, sorted{static_cast<std::size_t>(n_keys)};
  std::uint64_t* tk = tri_keys.data();
  const int* off = offset.data();
  ForEachIndex(cubes, [=] __device__(int c) {
    if (cnt[c] == 0) return;
    const BrickCoord b = coords[c / 512];
    const int i = c % 512;
    std::uint64_t t[mesh::kMaxCubeTriangles][3];
    const int nt = mesh::CubeTriangles(view, b.x * 8 + (i & 7), b.y * 8 + ((i >> 3) & 7), b.z * 8 + (i >> 6), t);
    for (int k = 0; k < nt; ++k)
      for (int j = 0; j < 3; ++j) tk[3 * (off[c] + k) + j] = t[k][j];
  });
  // 2. Distinct edges in key order: the vertices.
  bytes = 0;
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(nullptr, bytes, tk, sorted.data(), n_keys));
  DeviceBuffer<std::uint64_t> unique{static_cast<std::size_t>(n_keys)};
  DeviceBuffer<int> n_unique{1};
  std::size_t bytes2 = 0;
  HDRF_CUDA_CHECK(cub::DeviceSelect::Unique(nullptr, bytes2, sorted.data(), unique.data(), n_unique.data(), n_keys));
  temp = DeviceBuffer<std::uint8_t>{std::max({bytes, bytes2, std::size_t(16)})};
  bytes = temp.size();
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(temp.data(), bytes, tk, sorted.data(), n_keys));
  bytes = temp.size();
  HDRF_CUDA_CHECK(cub::DeviceSelect::Unique(temp.data(), bytes, sorted.data(), unique.data(), n_unique.data(), n_keys));
  int nv = 0;
  HDRF_CUDA_CHECK(cudaMemcpy(&nv, n_unique.data(), sizeof(int), cudaMemcpyDeviceToHost));
  DeviceBuffer<Float3> pos{static_cast<std::size_t>(nv)}, nrm{static_cast<std::size_t>(nv)}, rad{static_cast<std::size_t>(nv)};
  const std::uint64_t* uk = unique.data();
  Float3 *pp = pos.data(), *pn = nrm.data(), *pr = rad.data();
  ForEachIndex(nv, [=] __device__(int i) { mesh::EdgeVertex(view, uk[i], &pp[i], &pn[i], &pr[i]); });
  // 3. Triangles as vertex indices (binary search of their keys), facing the free space.
  DeviceBuffer<std::int32_t> tris{static_cast<std::size_t>(n_keys)};
  std::int32_t* tr = tris.data();
  ForEachIndex(n_tri, [=] __device__(int t) {
    std::int32_t idx[3];
    for (int j = 0; j < 3; ++j) {
      const std::uint64_t key = tk[3 * t + j];
      int lo = 0, hi = nv;
      while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (uk[mid] < key) lo = mid + 1;
        else hi = mid;
      }
      idx[j] = lo;
    }
    mesh::OrientTriangle(pp, pn, idx);
    for (int j = 0; j < 3; ++j) tr[3 * t + j] = idx[j];
  });
  m.position.resize(std::size_t(nv));
  m.normal.resize(std::size_t(nv));
  m.radiance.resize(std::size_t(nv));
  m.triangles.resize(std::size_t(n_tri));
  pos.Download(m.position.data());
  nrm.Download(m.normal.data());
  rad.Download(m.radiance.data());
  cuda::CopyDeviceToHost(m.triangles.data(), tr, std::size_t(n_keys) * sizeof(std::int32_t));
  return m;
}

const volume::Volume& CudaBackend::HostVolume() {
  if (mirror_fresh_) return mirror_;
  std::vector<int> index(index_.size());
  index_.Download(index.data());
  std::vector<std::uint8_t> pool(std::size_t(allocated_) * 512 * std::size_t(vbytes_));
  std::vector<BrickCoord> bc(static_cast<std::size_t>(allocated_));
  if (allocated_ > 0) {
    cuda::CopyDeviceToHost(pool.data(), pool_.data(), pool.size());
    cuda::CopyDeviceToHost(bc.data(), coords_.data(), bc.size() * sizeof(BrickCoord));
  }
  std::vector<std::array<int, 3>> coords(bc.size());
  for (std::size_t i = 0; i < bc.size(); ++i) coords[i] = {bc[i].x, bc[i].y, bc[i].z};
  mirror_.Assign(std::move(index), std::move(pool), std::move(coords), full_);
  mirror_fresh_ = true;
  return mirror_;
}

}  // namespace hdrf::pipeline::cuda_detail

namespace hdrf::pipeline {
std::unique_ptr<Backend> MakeCudaBackend(const BackendSetup& setup) {
  std::string why;
  if (!CudaAvailable(&why)) throw Error("the CUDA backend cannot run: " + why);
  return std::make_unique<cuda_detail::CudaBackend>(setup);
}
}  // namespace hdrf::pipeline
