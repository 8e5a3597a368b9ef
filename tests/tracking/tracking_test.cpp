#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "pipeline/pipeline.h"
#include "sim/builtin_sensor.h"
#include "tracking/tracking.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

TEST(Tracking, FollowsTheCameraThroughFourfoldExposureJumps) {
  const auto frames = Frames(6, sim::AeMode::kList, false, {6, 24});
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const SensorInfo s = sim::BuiltinXtionProfile();
  for (auto kind : {tracking::TrackerKind::kNr, tracking::TrackerKind::kNrIcp, tracking::TrackerKind::kIcp}) {
    pipeline::PipelineOptions po;
    po.tracker.kind = kind;
    pipeline::Pipeline pipe(po, cam, s);
    const Pose T0inv = frames[0].T_world_camera.inverse();
    double worst_t = 0, worst_r = 0;
    Pose prev_est = Pose::Identity(), prev_gt = Pose::Identity();
    for (const auto& f : frames) {
      pipeline::FrameInput in;
      in.color = f.color.Clone();
      in.depth_m = Metres(f.depth);
      const auto rep = pipe.Process(in);
      const Pose gt = T0inv * f.T_world_camera;
      // Error of the frame-to-frame motion (what one tracking step is responsible for).
      const Pose err = (prev_gt.inverse() * gt).inverse() * (prev_est.inverse() * rep.T_world_camera);
      prev_est = rep.T_world_camera;
      prev_gt = gt;
      worst_t = std::max(worst_t, se3::TranslationNorm(err));
      worst_r = std::max(worst_r, se3::RotationAngle(err) * 180 / M_PI);
      EXPECT_FALSE(rep.tracking.lost) << rep.tracking.why;
    }
    std::printf("%s: worst frame-to-frame motion error over 6 frames alternating 6 and 24 ms: "
                "%.2f mm, %.3f deg\n", tracking::TrackerName(kind), 1000 * worst_t, worst_r);
    // The model is one or two noisy frames thin here; over long scans errors are far smaller
    // (tests/cli ScanAccuracy).
    EXPECT_LT(worst_t, kind == tracking::TrackerKind::kNr ? 0.012 : 0.006);
    EXPECT_LT(worst_r, 0.3);
  }
}

}  // namespace
}  // namespace hdrf
