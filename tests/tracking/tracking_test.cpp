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

namespace hdrf::tracking {
namespace {

// One ICP term: a live point 1 cm in front of a reference plane facing the camera adds the
// point-to-plane residual with the Jacobian of the plane's normal; a normal turned away
// beyond the angle gate, or a point beyond the distance gate, adds nothing.
TEST(IcpTerm, PointToPlaneResidualAndGates) {
  const PinholeCamera cam{4, 4, 4.f, 4.f, 1.5f, 1.5f};
  Image<Float3> live_v(4, 4), live_n(4, 4, Float3{0, 0, -1}), ref_v(4, 4), ref_n(4, 4, Float3{0, 0, -1});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      live_v(x, y) = cam.BackProject(float(x), float(y), 0.99f);
      ref_v(x, y) = cam.BackProject(float(x), float(y), 1.0f);
    }
  TrackerOptions o;
  const Pose I = Pose::Identity();
  const ReferenceView ref{cam, View(ref_v), View(ref_n), {}};
  const LiveView live{cam, View(live_v), View(live_n), {}, {}, {}, {}};
  IcpArgs a = MakeIcpArgs(ref, I, live, I, o);
  GnSystem acc;
  ASSERT_TRUE(IcpTerm(a, 1, 1, acc));
  EXPECT_EQ(acc.icp_n(), 1.0);
  // r = n.(p - m) = (0,0,-1).(0,0,-0.01) = 0.01 m, within the Huber threshold (1.345 sigma):
  // full weight, and the squared residual r^2 in m^2.
  EXPECT_DOUBLE_EQ(acc.icp_w(), 1.0);
  EXPECT_NEAR(acc.icp_r2(), 1e-4, 1e-7);
  live_n(1, 1) = Float3{0, -1, 0};  // 90 degrees off the reference normal
  GnSystem none;
  EXPECT_FALSE(IcpTerm(a, 1, 1, none));
  live_n(1, 1) = Float3{0, 0, -1};
  live_v(1, 1) = cam.BackProject(1.f, 1.f, 0.8f);  // 20 cm off: beyond icp_max_dist_m
  EXPECT_FALSE(IcpTerm(a, 1, 1, none));
  EXPECT_EQ(none.icp_n(), 0.0);
}

}  // namespace
}  // namespace hdrf::tracking
