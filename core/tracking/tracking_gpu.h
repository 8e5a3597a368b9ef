// The tracker on the GPU (tracking_cuda.cu; CUDA builds only): the pyramids through the
// shared drivers (pyramid_driver.h) and the Gauss-Newton sums of the same per-pixel terms
// (tracking_impl.h) as AccumulateCpu, reduced in a fixed order, and the iterations
// themselves on the device. Views are device views.
#pragma once

#include <cuda_runtime_api.h>

#include <memory>
#include <vector>

#include "tracking/pyramid_driver.h"
#include "tracking/tracking.h"

namespace hdrf::tracking {

void BuildLiveLevelOnGpu(const LiveLevelViews* finer, const LiveLevelViews& level, float max_normal_jump_m);
void BuildReferenceLevelOnGpu(const ReferenceLevelViews& finer, const ReferenceLevelViews& level);
void PlaceInWorldOnGpu(ImageView<const Float3> vertex_c, ImageView<const Float3> normal_c,
                       const RigidTransform& T_world_camera, ImageView<Float3> vertex_w, ImageView<Float3> normal_w);

class GpuNormalEquations {
 public:
  GpuNormalEquations();
  ~GpuNormalEquations();
  GnSystem Accumulate(const ReferenceView& ref, const Pose& T_world_ref, const LiveView& live,
                      const Pose& T_world_live, const TrackerOptions& o);
  // The Gauss-Newton iterations of RunGaussNewton (tracking.h) in one cooperative kernel
  // (each iteration a sum by every block, then the step of gn_step.h by the first): the pose
  // stays on the device between iterations, and the result is read back once, with the
  // finest level's valid pixels (last_valid()). `levels`: finest first, each the reference's
  // and the live frame's views.
  struct Level {
    ReferenceView ref;
    LiveView live;
  };
  GaussNewtonRun RunOnDevice(const std::vector<Level>& levels, const Pose& T_world_ref, const Pose& initial,
                             const TrackerOptions& o, const MotionPrior* prior);
  // RunOnDevice in two halves: the run queued on the default stream (after its work), where
  // more may be queued behind it (at the pose it leaves in device memory: device_pose());
  // then waited for and read back.
  void QueueRun(const std::vector<Level>& levels, const Pose& T_world_ref, const Pose& initial,
                const TrackerOptions& o, const MotionPrior* prior);
  GaussNewtonRun FinishRun();
  const PoseD* device_pose() const;  // the run's pose, in device memory
  long CountLiveVertices(ImageView<const Float3> vertex_c);       // with depth (z > 0)
  long CountReferenceVertices(ImageView<const Float3> vertex_w);  // any non-zero vertex
  // Both counts of the finest level of the last RunOnDevice, made inside its run.
  struct Valid {
    long live = 0, reference = 0;
  };
  Valid last_valid() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hdrf::tracking
