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
}  // namespace

struct GpuNormalEquations::Impl {
  par::Reducer reducer{GnSystem::kSize};
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
