#include <array>

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
struct Count1 {
  double v[1] = {0};
};
struct Count2 {
  double v[2] = {0, 0};
};

// What changes from frame to frame (uploaded by the run's first step): the start, the
// prior, and each level's term arguments (the pose's parts replaced iteration by iteration).
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
};

__global__ void StartRun(DeviceTrack* d) {
  DeviceRun& s = d->run;
  s.T = d->frame.initial;
  s.iterations = 0;
  for (int k = 0; k < 4; ++k) s.level_iterations[k] = 0;
  for (int k = 0; k < GnSystem::kSize; ++k) s.last.v[k] = 0;
}

// The term arguments of a level at the run's current pose.
__device__ void SetPoseArgs(DeviceTrack* d, int level) {
  DeviceRun& s = d->run;
  s.icp = d->frame.icp[level];
  s.photo = d->frame.photo[level];
}
// Within a level only the pose's parts change.
__device__ void SetPose(DeviceRun& s) {
  const PoseD T = s.T;
  s.icp.T_world_live = ToRigid(T);
  for (int k = 0; k < 9; ++k) s.icp.R_world_live[k] = T.R[k];
  s.photo.T_live_world = ToRigid(Inverse(T));
}
__global__ void StartLevel(DeviceTrack* d, int level) {
  SetPoseArgs(d, level);
  SetPose(d->run);
}
__global__ void KeepValid(DeviceTrack* d, const double* sums) {
  d->run.valid[0] = sums[0];
  d->run.valid[1] = sums[1];
}

// The counts CountLiveVertices and CountReferenceVertices make, in one pass.
__device__ void CountValid(const IcpArgs& a, int x, int y, Count2& acc) {
  acc.v[0] += a.live_vertex(x, y).z > 0.f ? 1.0 : 0.0;
  const Float3 p = a.ref_vertex(x, y);
  acc.v[1] += (p.x != 0.f || p.y != 0.f || p.z != 0.f) ? 1.0 : 0.0;
}

// One step from the level's sums (a kernel of its own: inside the sum's kernel its registers
// would be the whole sum's), and whether the level goes on: fewer steps than its cap, the
// last neither converged nor failed. GnStep's parts that need only the sums and the pose run
// side by side, one warp each (the step is one thread's chain of divisions and square roots):
// the prior's residual, the check for weak directions, and the factor of H as solved where
// there are none (the common case; where there are, the first thread raises them and
// factors again). The same operations on the same values as GnStep: the same bits.
constexpr int kStepWarps = 3;
__global__ void __launch_bounds__(32 * kStepWarps)
    TakeStep(DeviceTrack* d, const double* sums, int level, int cap, cudaGraphConditionalHandle go_on) {
  __shared__ double e[6], L[36];
  __shared__ bool weak, factored;
  DeviceRun& s = d->run;
  const StepPrior& prior = d->frame.prior;
  const int part = threadIdx.x / 32;
  GnSystem acc;
  double H[36], g[6];
  if (threadIdx.x % 32 == 0) {
    for (int k = 0; k < GnSystem::kSize; ++k) acc.v[k] = sums[k];
    StepSystem(acc, H, g);
    if (part == 0 && prior.on) {
      PriorResidual(prior, s.T, e);
    } else if (part == 1) {
      weak = prior.on && prior.floor > 0 && WeakDirections(prior, H);
    } else if (part == 2) {
      if (prior.on) PriorInformation(prior, H);
      Damp(H);
      double Lr[36];
      factored = Cholesky6(H, Lr);
      for (int k = 0; k < 36; ++k) L[k] = Lr[k];
    }
  }
  __syncthreads();
  if (threadIdx.x != 0) return;
  int out = kStepTooFew;
  if (EnoughTerms(acc)) {
    double Lr[36];
    bool ok = factored;
    if (prior.on && weak) {
      double ev[6];
      for (int k = 0; k < 6; ++k) ev[k] = e[k];
      RaiseWeakDirections(prior, ev, H, g);
      PriorInformation(prior, H);
      Damp(H);
      ok = Cholesky6(H, Lr);
    } else {
      for (int k = 0; k < 36; ++k) Lr[k] = L[k];
    }
    if (prior.on) {
      double ev[6];
      for (int k = 0; k < 6; ++k) ev[k] = e[k];
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
  cudaGraphSetConditional(go_on, more ? 1u : 0u);
}

// What a captured run depends on besides its frame's parameters.
struct GraphShape {
  int levels = 0;
  std::array<int, 4> iterations{}, width{}, height{};
  bool icp = false, photo = false;
  bool operator==(const GraphShape&) const = default;
};
}  // namespace

struct GpuNormalEquations::Impl {
  par::Reducer reducer{GnSystem::kSize};
  par::Reducer count_reducer{2};  // the valid pixels' counts, beside the levels' sums
  DeviceBuffer<DeviceTrack> track{1};
  DeviceTrack* host = nullptr;  // pinned: the frame's parameters out, the run's state back
  cudaStream_t capture_stream = nullptr, body_stream = nullptr, count_stream = nullptr;
  cudaEvent_t fork = nullptr, join = nullptr;
  cudaGraphExec_t graph = nullptr;
  GraphShape shape;
  Valid valid;
  Impl() {
    HDRF_CUDA_CHECK(cudaMallocHost(&host, sizeof(DeviceTrack)));
    HDRF_CUDA_CHECK(cudaStreamCreate(&capture_stream));
    HDRF_CUDA_CHECK(cudaStreamCreate(&body_stream));
    HDRF_CUDA_CHECK(cudaStreamCreate(&count_stream));
    HDRF_CUDA_CHECK(cudaEventCreateWithFlags(&fork, cudaEventDisableTiming));
    HDRF_CUDA_CHECK(cudaEventCreateWithFlags(&join, cudaEventDisableTiming));
  }
  ~Impl() {
    if (graph) cudaGraphExecDestroy(graph);
    cudaEventDestroy(join);
    cudaEventDestroy(fork);
    cudaStreamDestroy(count_stream);
    cudaStreamDestroy(body_stream);
    cudaStreamDestroy(capture_stream);
    cudaFreeHost(host);
  }
};

// The whole run as one CUDA graph: the parameters' upload, the start, each level's
// iterations as a loop node (its body one sum and the step, which says whether to go on),
// the state's read-back. Launched as one, it leaves the GPU nothing to wait for
// from the host and runs no more sums than the steps take; it is captured again only when
// its shape changes (levels, iteration caps, sizes, terms).
namespace {
// What a capture uses: the sums' reducers, the run's state, the streams and events.
struct CaptureParts {
  par::Reducer &reducer, &count_reducer;
  DeviceTrack *d, *host;
  cudaStream_t capture_stream, body_stream, count_stream;
  cudaEvent_t fork, join;
};
cudaGraphExec_t CaptureRun(const CaptureParts& m, const GraphShape& g) {
  par::Reducer& reducer = m.reducer;
  DeviceTrack* d = m.d;
  DeviceTrack* host = m.host;
  const cudaStream_t stream = m.capture_stream, body_stream = m.body_stream;
  constexpr cudaStreamCaptureMode kMode = cudaStreamCaptureModeThreadLocal;
  HDRF_CUDA_CHECK(cudaStreamBeginCapture(stream, kMode));
  HDRF_CUDA_CHECK(cudaMemcpyAsync(&d->frame, &host->frame, sizeof(FrameParams), cudaMemcpyHostToDevice, stream));
  StartRun<<<1, 1, 0, stream>>>(d);
  const DeviceTrack* rd = d;
  // The finest level's valid pixels (the tracking's judge weighs the matches against them),
  // on a branch of their own beside the levels, joined before the read-back.
  HDRF_CUDA_CHECK(cudaEventRecord(m.fork, stream));
  HDRF_CUDA_CHECK(cudaStreamWaitEvent(m.count_stream, m.fork, 0));
  m.count_reducer.SumOnDevice<Count2>(
      g.width[0], g.height[0], [=] __device__(int x, int y, Count2& acc) { CountValid(rd->frame.icp[0], x, y, acc); },
      m.count_stream);
  KeepValid<<<1, 1, 0, m.count_stream>>>(d, m.count_reducer.device_sums());
  HDRF_CUDA_CHECK(cudaEventRecord(m.join, m.count_stream));
  const bool use_icp = g.icp, use_photo = g.photo;
  for (int l = g.levels - 1; l >= 0; --l) {
    const int iters = g.iterations[std::size_t(g.levels - 1 - l)];
    if (iters <= 0) continue;
    StartLevel<<<1, 1, 0, stream>>>(d, l);
    // The loop node, after what the capture holds so far.
    cudaStreamCaptureStatus status;
    cudaGraph_t captured = nullptr;
    const cudaGraphNode_t* deps = nullptr;
    std::size_t n_deps = 0;
    HDRF_CUDA_CHECK(cudaStreamGetCaptureInfo(stream, &status, nullptr, &captured, &deps, nullptr, &n_deps));
    cudaGraphConditionalHandle go_on;
    HDRF_CUDA_CHECK(cudaGraphConditionalHandleCreate(&go_on, captured, 1, cudaGraphCondAssignDefault));
    cudaGraphNodeParams p{};
    p.type = cudaGraphNodeTypeConditional;
    p.conditional.handle = go_on;
    p.conditional.type = cudaGraphCondTypeWhile;
    p.conditional.size = 1;
    cudaGraphNode_t loop;
    HDRF_CUDA_CHECK(cudaGraphAddNode(&loop, captured, deps, nullptr, n_deps, &p));
    HDRF_CUDA_CHECK(cudaStreamUpdateCaptureDependencies(stream, &loop, nullptr, 1, cudaStreamSetCaptureDependencies));
    HDRF_CUDA_CHECK(cudaStreamBeginCaptureToGraph(body_stream, p.conditional.phGraph_out[0], nullptr, nullptr, 0, kMode));
    reducer.SumOnDevice<GnSystem>(
        g.width[std::size_t(l)], g.height[std::size_t(l)],
        [=] __device__(int x, int y, GnSystem& acc) {
          if (use_icp) IcpTerm(rd->run.icp, x, y, acc);
          if (use_photo) PhotoTerm(rd->run.photo, x, y, acc);
        },
        body_stream);
    TakeStep<<<1, 32 * kStepWarps, 0, body_stream>>>(d, reducer.device_sums(), l, iters, go_on);
    cudaGraph_t body = nullptr;
    HDRF_CUDA_CHECK(cudaStreamEndCapture(body_stream, &body));
  }
  HDRF_CUDA_CHECK(cudaStreamWaitEvent(stream, m.join, 0));
  HDRF_CUDA_CHECK(cudaMemcpyAsync(&host->run, &d->run, sizeof(DeviceRun), cudaMemcpyDeviceToHost, stream));
  cudaGraph_t whole = nullptr;
  HDRF_CUDA_CHECK(cudaStreamEndCapture(stream, &whole));
  cudaGraphExec_t graph = nullptr;
  const cudaError_t made = cudaGraphInstantiate(&graph, whole, 0);
  cudaGraphDestroy(whole);
  HDRF_CUDA_CHECK(made);
  return graph;
}
}  // namespace

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
  GraphShape g;
  g.levels = std::min(o.levels, std::min(int(levels.size()), 4));
  g.icp = o.kind == TrackerKind::kIcp || o.kind == TrackerKind::kNrIcp;
  g.photo = o.kind != TrackerKind::kIcp;
  FrameParams& f = m.host->frame;
  f.initial = ToPoseD(initial);
  f.prior = MakeStepPrior(o, prior);
  for (int l = 0; l < g.levels; ++l) {
    const Level& L = levels[std::size_t(l)];
    g.iterations[std::size_t(l)] = o.iterations[std::size_t(l)];
    g.width[std::size_t(l)] = L.live.cam.width;
    g.height[std::size_t(l)] = L.live.cam.height;
    f.icp[l] = MakeIcpArgs(L.ref, T_world_ref, L.live, initial, o);
    f.photo[l] = MakePhotoArgs(L.ref, L.live, initial, o);
  }
  if (!m.graph || !(g == m.shape)) {
    if (m.graph) HDRF_CUDA_CHECK(cudaGraphExecDestroy(m.graph));
    m.graph = nullptr;
    m.graph = CaptureRun({m.reducer, m.count_reducer, m.track.data(), m.host, m.capture_stream, m.body_stream, m.count_stream,
                          m.fork, m.join},
                         g);
    m.shape = g;
  }
  // On the default stream, after whatever it has queued (the live pyramid, the reference):
  // no event between streams to wait on.
  HDRF_CUDA_CHECK(cudaGraphLaunch(m.graph, nullptr));
}

GaussNewtonRun GpuNormalEquations::FinishRun() {
  Impl& m = *impl_;
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
  const Count1 c = impl_->reducer.Sum<Count1>(v.width, v.height, [=] __device__(int x, int y, Count1& acc) {
    acc.v[0] += v(x, y).z > 0.f ? 1.0 : 0.0;
  });
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
