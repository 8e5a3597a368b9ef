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

// A tracking run's state on the device: the pose, when the level stops, the counts, the
// finest level's last system, and the term arguments at the current pose.
struct DeviceRun {
  PoseD T;
  int stop, skip, iterations, level_iterations[4];
  GnSystem last;
  IcpArgs icp;
  PhotoArgs photo;
};

// Before each sum: skipped once the level has stopped (its first iteration always runs),
// else the term arguments of the level at the pose the last step left.
__global__ void PrepareIteration(DeviceRun* s, IcpArgs icp, PhotoArgs photo, bool first) {
  if (!first && s->stop) {
    s->skip = 1;
    return;
  }
  s->skip = 0;
  const PoseD T = s->T;
  icp.T_world_live = ToRigid(T);
  for (int k = 0; k < 9; ++k) icp.R_world_live[k] = T.R[k];
  photo.T_live_world = ToRigid(Inverse(T));
  s->icp = icp;
  s->photo = photo;
}
}  // namespace

struct GpuNormalEquations::Impl {
  par::Reducer reducer{GnSystem::kSize};
  DeviceBuffer<DeviceRun> run{1};
  DeviceRun* host = nullptr;  // pinned
  Impl() { HDRF_CUDA_CHECK(cudaMallocHost(&host, sizeof(DeviceRun))); }
  ~Impl() { cudaFreeHost(host); }
};

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
  Impl& m = *impl_;
  *m.host = DeviceRun{};
  m.host->T = ToPoseD(initial);
  HDRF_CUDA_CHECK(cudaMemcpyAsync(m.run.data(), m.host, sizeof(DeviceRun), cudaMemcpyHostToDevice, 0));
  const StepPrior sp = MakeStepPrior(o, prior);
  const bool use_icp = o.kind == TrackerKind::kIcp || o.kind == TrackerKind::kNrIcp;
  const bool use_photo = o.kind != TrackerKind::kIcp;
  DeviceRun* s = m.run.data();
  const int n = std::min(o.levels, int(levels.size()));
  for (int l = n - 1; l >= 0; --l) {
    const Level& L = levels[std::size_t(l)];
    // The pose's parts of these are replaced on the device, iteration by iteration.
    const IcpArgs icp = MakeIcpArgs(L.ref, T_world_ref, L.live, initial, o);
    const PhotoArgs photo = MakePhotoArgs(L.ref, L.live, initial, o);
    const int iters = o.iterations[std::size_t(n - 1 - l)];
    for (int it = 0; it < iters; ++it) {
      PrepareIteration<<<1, 1>>>(s, icp, photo, it == 0);
      HDRF_CUDA_CHECK_LAUNCH();
      const DeviceRun* rs = s;
      m.reducer.SumOnDevice<GnSystem>(
          L.live.cam.width, L.live.cam.height,
          [=] __device__(int x, int y, GnSystem& acc) {
            if (use_icp) IcpTerm(rs->icp, x, y, acc);
            if (use_photo) PhotoTerm(rs->photo, x, y, acc);
          },
          [=] __device__() { return rs->skip == 0; },
          [=] __device__(const double* sums) {
            GnSystem acc;
            for (int k = 0; k < GnSystem::kSize; ++k) acc.v[k] = sums[k];
            const int out = GnStep(acc, sp, &s->T);
            if (out == kStepTooFew || out == kStepNotFinite) {
              s->stop = 1;
              return;
            }
            ++s->iterations;
            ++s->level_iterations[l];
            if (l == 0) s->last = acc;
            s->stop = out == kStepConverged ? 1 : 0;
          });
    }
  }
  HDRF_CUDA_CHECK(cudaMemcpyAsync(m.host, m.run.data(), sizeof(DeviceRun), cudaMemcpyDeviceToHost, 0));
  HDRF_CUDA_CHECK(cudaStreamSynchronize(0));
  GaussNewtonRun run;
  run.T_world_camera = FromPoseD(m.host->T);
  run.last = m.host->last;
  run.iterations = m.host->iterations;
  for (int k = 0; k < 4; ++k) run.level_iterations[std::size_t(k)] = m.host->level_iterations[k];
  return run;
}

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
