#include <cooperative_groups.h>

#include <algorithm>
#include <atomic>

#include "common/parallel_cuda.cuh"
#include "tracking/tracking_gpu.h"

namespace hdrf::tracking {

void BuildLiveLevelOnGpu(const LiveLevelViews* finer, const LiveLevelViews& level, float max_normal_jump_m) {
  BuildLiveLevel(par::Gpu{}, finer, level, max_normal_jump_m);
}
void BuildReferenceLevelOnGpu(const ReferenceLevelViews& finer, const ReferenceLevelViews& level) {
  BuildReferenceLevel(par::Gpu{}, finer, level);
}
void PlaceInWorldOnGpu(ImageView<const Float3> vertex_c, ImageView<const Float3> normal_c,
                       const RigidTransform& T_world_camera, ImageView<Float3> vertex_w, ImageView<Float3> normal_w) {
  PlaceInWorld(par::Gpu{}, vertex_c, normal_c, T_world_camera, vertex_w, normal_w);
}

namespace {
namespace cg = cooperative_groups;
struct Count1 {
  double v[1] = {0};
};

// What changes from frame to frame (uploaded before the run): the start, the prior, and each
// level's term arguments (the pose's parts replaced iteration by iteration).
struct FrameParams {
  PoseD initial;
  StepPrior prior;
  IcpArgs icp[4];
  PhotoArgs photo[4];
};
// A tracking run's state on the device: the pose, the counts, the
// finest level's last system, and the term arguments at the current pose.
struct DeviceRun {
  PoseD T;
  int iterations, level_iterations[4];
  double valid[2];  // the finest level's live pixels with depth, and reference pixels with a vertex
  GnSystem last;
  IcpArgs icp;
  PhotoArgs photo;
};
struct DeviceTrack {
  FrameParams frame;
  DeviceRun run;
  int go;  // whether the level goes on after the last step (the lead block's word to the others)
};

// What the run depends on besides its frame's parameters.
struct RunShape {
  int levels = 0;
  int iterations[4] = {}, width[4] = {}, height[4] = {};  // iterations: coarsest first, as TrackerOptions
  bool icp = false, photo = false;
};

__device__ void StartRun(DeviceTrack* d) {
  DeviceRun& s = d->run;
  s.T = d->frame.initial;
  s.iterations = 0;
  for (int k = 0; k < 4; ++k) s.level_iterations[k] = 0;
  for (int k = 0; k < GnSystem::kSize; ++k) s.last.v[k] = 0;
}

// Within a level only the pose's parts of the term arguments change.
__device__ void SetPose(const PoseD& T, IcpArgs& icp, PhotoArgs& photo) {
  icp.T_world_live = ToRigid(T);
  for (int k = 0; k < 9; ++k) icp.R_world_live[k] = T.R[k];
  photo.T_live_world = ToRigid(Inverse(T));
}
__device__ void SetPose(DeviceRun& s) { SetPose(s.T, s.icp, s.photo); }
// The next level to run after `level` (finer, with iterations), or -1.
__device__ int NextLevel(const RunShape& g, int level) {
  for (int l = level - 1; l >= 0; --l)
    if (g.iterations[g.levels - 1 - l] > 0) return l;
  return -1;
}

// One step from the level's sums, and whether the level goes on: fewer steps than its cap,
// the last neither converged nor failed (the answer in thread 0). GnStep's parts that need
// only the sums and the pose run side by side, one warp each (the step is one thread's chain
// of divisions and square roots): the prior's residual, the check for weak directions, and
// the factor of H as solved where there are none (the common case; where there are, the first
// thread raises them and factors again). The same operations on the same values as GnStep:
// the same bits. Every thread of the block (at least kStepWarps warps) calls it.
constexpr int kStepWarps = 3;
struct StepShared {
  double e[6], L[36];
  bool weak, factored;
};
__device__ __noinline__ bool StepOnBlock(DeviceRun& s, const StepPrior& prior, const double* sums, int level, int cap,
                                         StepShared& sh) {
  const int part = threadIdx.x / 32;
  GnSystem acc;
  double H[36], g[6];
  if (threadIdx.x % 32 == 0 && part < kStepWarps) {
    for (int k = 0; k < GnSystem::kSize; ++k) acc.v[k] = sums[k];
    StepSystem(acc, H, g);
    if (part == 0 && prior.on) {
      PriorResidual(prior, s.T, sh.e);
    } else if (part == 1) {
      sh.weak = prior.on && prior.floor > 0 && WeakDirections(prior, H);
    } else if (part == 2) {
      if (prior.on) PriorInformation(prior, H);
      Damp(H);
      double Lr[36];
      sh.factored = Cholesky6(H, Lr);
      for (int k = 0; k < 36; ++k) sh.L[k] = Lr[k];
    }
  }
  __syncthreads();
  if (threadIdx.x != 0) return false;
  int out = kStepTooFew;
  if (EnoughTerms(acc)) {
    double Lr[36];
    bool ok = sh.factored;
    if (prior.on && sh.weak) {
      double ev[6];
      for (int k = 0; k < 6; ++k) ev[k] = sh.e[k];
      RaiseWeakDirections(prior, ev, H, g);
      PriorInformation(prior, H);
      Damp(H);
      ok = Cholesky6(H, Lr);
    } else {
      for (int k = 0; k < 36; ++k) Lr[k] = sh.L[k];
    }
    if (prior.on) {
      double ev[6];
      for (int k = 0; k < 6; ++k) ev[k] = sh.e[k];
      PriorGradient(prior, ev, g);
    }
    out = ok ? SolveAndMove(Lr, g, &s.T) : kStepNotFinite;
  }
  bool more = false;
  if (out == kStepTaken || out == kStepConverged) {
    ++s.iterations;
    ++s.level_iterations[level];
    if (level == 0) s.last = acc;
    more = out == kStepTaken && s.level_iterations[level] < cap;
  }
  if (more) SetPose(s);
  return more;
}

// The run's sums are those of par::Reducer (its blocks, their partials and the order they are
// added in: the same device functions, so the same bits): `kSumBlocks` blocks of kThreads
// threads over a level's pixels. The run's kernel may have fewer blocks resident: each then
// makes the partials of several of those blocks in turn.
constexpr int kThreads = par::Reducer::kThreads;
constexpr int kSumBlocks = par::Reducer::kBlocks;
constexpr int K = GnSystem::kSize;
constexpr int G = par::detail::kPartialGroups<K>;
__host__ __device__ constexpr int SumBlocks(int n) {
  const int b = (n + kThreads - 1) / kThreads;
  return b < 1 ? 1 : b > kSumBlocks ? kSumBlocks : b;
}

// A block's copy of the run's term arguments, read through L2 (the lead block wrote them
// during this launch: another block's L1 may hold what they were).
template <typename T>
__device__ void CopyThroughL2(const T* from, T* to) {
  static_assert(sizeof(T) % sizeof(unsigned) == 0);
  const unsigned* f = reinterpret_cast<const unsigned*>(from);
  unsigned* t = reinterpret_cast<unsigned*>(to);
  for (int i = threadIdx.x; i < int(sizeof(T) / sizeof(unsigned)); i += blockDim.x) t[i] = __ldcg(f + i);
}
// The term arguments of a level at the run's current pose, made by a whole block (every
// thread calls it): the level's arguments copied a word a thread, then the pose's parts set
// by the first thread. (One thread copying them took about 5 us a level on an H100.)
__device__ void StartLevel(DeviceTrack* d, int level) {
  CopyThroughL2(&d->frame.icp[level], &d->run.icp);
  CopyThroughL2(&d->frame.photo[level], &d->run.photo);
  __syncthreads();
  if (threadIdx.x == 0) SetPose(d->run);
}

// One sum block's partial sums of a level's terms. Not inlined, nor is the step: each is
// given the registers it needs, not the other's too.
__device__ __noinline__ void BlockPartial(int b, int nb, int w, int h, const IcpArgs& icp, const PhotoArgs& photo,
                                          bool use_icp, bool use_photo, double (*sh)[K], double* partial) {
  GnSystem acc;
  par::detail::AddBlockPixels(
      b, nb, w, h,
      [&](int x, int y, GnSystem& a) {
        if (use_icp) IcpTerm(icp, x, y, a);
        if (use_photo) PhotoTerm(photo, x, y, a);
      },
      acc);
  par::detail::StoreBlockPartial(acc, b, sh, partial);
}

// The finest level's valid pixels (live with depth, reference with a vertex), added to
// counts[0..1] (zero before the run; integers, so their order does not matter) by `blocks`
// blocks, this one the `block`-th.
__device__ void CountValid(const IcpArgs& a, int w, int h, int block, int blocks, unsigned* counts,
                           unsigned* block_counts) {
  unsigned live = 0, ref = 0;
  for (int i = block * kThreads + int(threadIdx.x); i < w * h; i += blocks * kThreads) {
    const int x = i % w, y = i / w;
    live += a.live_vertex(x, y).z > 0.f ? 1u : 0u;
    const Float3 p = a.ref_vertex(x, y);
    ref += (p.x != 0.f || p.y != 0.f || p.z != 0.f) ? 1u : 0u;
  }
  for (int off = 16; off > 0; off >>= 1) {
    live += __shfl_down_sync(0xffffffffu, live, off);
    ref += __shfl_down_sync(0xffffffffu, ref, off);
  }
  if (threadIdx.x == 0) block_counts[0] = 0, block_counts[1] = 0;
  __syncthreads();
  if ((threadIdx.x & 31) == 0) {
    atomicAdd(&block_counts[0], live);
    atomicAdd(&block_counts[1], ref);
  }
  __syncthreads();
  if (threadIdx.x == 0) {
    atomicAdd(&counts[0], block_counts[0]);
    atomicAdd(&counts[1], block_counts[1]);
  }
}

// The whole run, coarse to fine, in one cooperative launch: each step's sums made by every
// block, the grid synchronised, the lead block (0) adding the partials and taking the step
// (it writes the pose, the next arguments and whether to go on), the grid synchronised
// again. The first step's arguments each block makes itself from the frame's parameters, and
// the valid pixels are counted by the blocks the first level's sums leave idle (by all blocks
// first where there are none). As a CUDA graph with a loop node a level (a sum kernel and a
// step kernel an iteration) the run of a 640x480 frame took about 0.3 ms on an H100.
__global__ void __launch_bounds__(kThreads) RunKernel(DeviceTrack* d, RunShape g, double* partial, unsigned* counts) {
  const cg::grid_group grid = cg::this_grid();
  __shared__ alignas(16) unsigned char icp_raw[sizeof(IcpArgs)], photo_raw[sizeof(PhotoArgs)];
  IcpArgs& icp = *reinterpret_cast<IcpArgs*>(icp_raw);
  PhotoArgs& photo = *reinterpret_cast<PhotoArgs*>(photo_raw);
  __shared__ double red[kThreads / 32][K], group_sum[G][K], sums[K];
  __shared__ StepShared step;
  __shared__ unsigned block_counts[2];
  __shared__ int go;
  const int block = int(blockIdx.x), blocks = int(gridDim.x);
  const bool lead = block == 0;
  int level = NextLevel(g, g.levels);
  const int idle_from = level >= 0 ? SumBlocks(g.width[level] * g.height[level]) : blocks;
  const bool idle_count = idle_from < blocks;
  if (!idle_count) CountValid(d->frame.icp[0], g.width[0], g.height[0], block, blocks, counts, block_counts);
  if (lead) {
    if (threadIdx.x == 0) StartRun(d);
    if (level >= 0) StartLevel(d, level);
  }
  if (level < 0) grid.sync();  // (no step: the counts are read below)
  if (level >= 0 && threadIdx.x == 0) {
    icp = d->frame.icp[level];
    photo = d->frame.photo[level];
    SetPose(d->frame.initial, icp, photo);
  }
  __syncthreads();
  bool first = true;
  while (level >= 0) {
    const int cap = g.iterations[g.levels - 1 - level];
    const int w = g.width[level], h = g.height[level], nb = SumBlocks(w * h);
    if (!first) {
      CopyThroughL2(&d->run.icp, &icp);
      CopyThroughL2(&d->run.photo, &photo);
      __syncthreads();
    }
    for (int b = block; b < nb; b += blocks) BlockPartial(b, nb, w, h, icp, photo, g.icp, g.photo, red, partial);
    if (first && idle_count && block >= idle_from)
      CountValid(d->frame.icp[0], g.width[0], g.height[0], block - idle_from, blocks - idle_from, counts, block_counts);
    first = false;
    grid.sync();
    if (lead) {
      par::detail::AddPartials<K>(nb, partial, group_sum, sums);
      const bool more = StepOnBlock(d->run, d->frame.prior, sums, level, cap, step);
      if (threadIdx.x == 0) go = more ? 1 : 0;  // (the answer is thread 0's)
      __syncthreads();
      const int next = go ? -1 : NextLevel(g, level);
      if (next >= 0) StartLevel(d, next);
      if (threadIdx.x == 0) d->go = go;
    }
    grid.sync();
    if (threadIdx.x == 0) go = __ldcg(&d->go);
    __syncthreads();
    if (!go) level = NextLevel(g, level);
  }
  if (lead && threadIdx.x == 0) {
    d->run.valid[0] = double(__ldcg(&counts[0]));
    d->run.valid[1] = double(__ldcg(&counts[1]));
    counts[0] = 0;
    counts[1] = 0;
  }
}
}  // namespace

struct GpuNormalEquations::Impl {
  par::Reducer reducer{GnSystem::kSize};  // Accumulate's sums
  DeviceBuffer<DeviceTrack> track{1};
  DeviceBuffer<double> partial{std::size_t(kSumBlocks) * K};
  DeviceBuffer<unsigned> counts{2};
  DeviceTrack* host = nullptr;  // pinned: the frame's parameters out, the run's state back
  int blocks = 1;               // the run's blocks: as many as can be resident at once, at most kSumBlocks
  Valid valid;
  Impl() {
    HDRF_CUDA_CHECK(cudaMallocHost(&host, sizeof(DeviceTrack)));
    HDRF_CUDA_CHECK(cudaMemset(counts.data(), 0, 2 * sizeof(unsigned)));
    int per_sm = 0, sms = 0, device = 0;
    HDRF_CUDA_CHECK(cudaGetDevice(&device));
    HDRF_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
    HDRF_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, RunKernel, kThreads, 0));
    blocks = std::max(1, std::min(kSumBlocks, per_sm * sms));
  }
  ~Impl() { cudaFreeHost(host); }
};

namespace {
std::atomic<int> run_block_limit{0};
}
void SetTrackerRunBlockLimit(int most) { run_block_limit = std::max(0, most); }

GpuNormalEquations::GpuNormalEquations() : impl_(std::make_unique<Impl>()) {}
GpuNormalEquations::~GpuNormalEquations() = default;

GnSystem GpuNormalEquations::Accumulate(const ReferenceView& ref, const Pose& T_world_ref, const LiveView& live,
                                        const Pose& T_world_live, const TrackerOptions& o) {
  const bool use_icp = o.kind == TrackerKind::kIcp || o.kind == TrackerKind::kNrIcp;
  const bool use_photo = o.kind != TrackerKind::kIcp;
  const IcpArgs ia = MakeIcpArgs(ref, T_world_ref, live, T_world_live, o);
  const PhotoArgs pa = MakePhotoArgs(ref, live, T_world_live, o);
  // Live and reference levels have the same size: one pass adds both terms of a pixel.
  return impl_->reducer.Sum<GnSystem>(live.cam.width, live.cam.height, [=] __device__(int x, int y, GnSystem& acc) {
    if (use_icp) IcpTerm(ia, x, y, acc);
    if (use_photo) PhotoTerm(pa, x, y, acc);
  });
}

GaussNewtonRun GpuNormalEquations::RunOnDevice(const std::vector<Level>& levels, const Pose& T_world_ref,
                                               const Pose& initial, const TrackerOptions& o, const MotionPrior* prior) {
  QueueRun(levels, T_world_ref, initial, o, prior);
  return FinishRun();
}

const PoseD* GpuNormalEquations::device_pose() const { return &impl_->track.data()->run.T; }

void GpuNormalEquations::QueueRun(const std::vector<Level>& levels, const Pose& T_world_ref, const Pose& initial,
                                  const TrackerOptions& o, const MotionPrior* prior) {
  Impl& m = *impl_;
  RunShape g;
  g.levels = std::min(o.levels, std::min(int(levels.size()), 4));
  g.icp = o.kind == TrackerKind::kIcp || o.kind == TrackerKind::kNrIcp;
  g.photo = o.kind != TrackerKind::kIcp;
  FrameParams& f = m.host->frame;
  f.initial = ToPoseD(initial);
  f.prior = MakeStepPrior(o, prior);
  for (int l = 0; l < g.levels; ++l) {
    const Level& L = levels[std::size_t(l)];
    g.iterations[l] = o.iterations[std::size_t(l)];
    g.width[l] = L.live.cam.width;
    g.height[l] = L.live.cam.height;
    f.icp[l] = MakeIcpArgs(L.ref, T_world_ref, L.live, initial, o);
    f.photo[l] = MakePhotoArgs(L.ref, L.live, initial, o);
  }
  // On the default stream, after whatever it has queued (the live pyramid, the reference).
  DeviceTrack* d = m.track.data();
  HDRF_CUDA_CHECK(cudaMemcpyAsync(&d->frame, &m.host->frame, sizeof(FrameParams), cudaMemcpyHostToDevice, nullptr));
  double* partial = m.partial.data();
  unsigned* counts = m.counts.data();
  void* args[] = {&d, &g, &partial, &counts};
  const int limit = run_block_limit;
  const int blocks = limit > 0 ? std::min(limit, m.blocks) : m.blocks;
  HDRF_CUDA_CHECK(cudaLaunchCooperativeKernel(reinterpret_cast<const void*>(&RunKernel), dim3(blocks), dim3(kThreads),
                                              args, 0, nullptr));
}

GaussNewtonRun GpuNormalEquations::FinishRun() {
  Impl& m = *impl_;
  // The run's state read back behind whatever was queued after the run (the exposure estimate
  // at its pose starts as soon as the run ends).
  HDRF_CUDA_CHECK(cudaMemcpyAsync(&m.host->run, &m.track.data()->run, sizeof(DeviceRun), cudaMemcpyDeviceToHost, nullptr));
  HDRF_CUDA_CHECK(cudaStreamSynchronize(nullptr));
  const DeviceRun& r = m.host->run;
  GaussNewtonRun run;
  run.T_world_camera = FromPoseD(r.T);
  run.last = r.last;
  run.iterations = r.iterations;
  for (int k = 0; k < 4; ++k) run.level_iterations[std::size_t(k)] = r.level_iterations[k];
  m.valid = {long(r.valid[0]), long(r.valid[1])};
  return run;
}

GpuNormalEquations::Valid GpuNormalEquations::last_valid() const { return impl_->valid; }

long GpuNormalEquations::CountLiveVertices(ImageView<const Float3> v) {
  const Count1 c = impl_->reducer.Sum<Count1>(
      v.width, v.height, [=] __device__(int x, int y, Count1& acc) { acc.v[0] += v(x, y).z > 0.f ? 1.0 : 0.0; });
  return long(c.v[0]);
}

long GpuNormalEquations::CountReferenceVertices(ImageView<const Float3> v) {
  const Count1 c = impl_->reducer.Sum<Count1>(v.width, v.height, [=] __device__(int x, int y, Count1& acc) {
    const Float3 p = v(x, y);
    acc.v[0] += (p.x != 0.f || p.y != 0.f || p.z != 0.f) ? 1.0 : 0.0;
  });
  return long(c.v[0]);
}

}  // namespace hdrf::tracking
