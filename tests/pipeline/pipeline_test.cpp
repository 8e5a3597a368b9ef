#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "pipeline/pipeline.h"
#include "pipeline/scan_session.h"
#include "sim/builtin_sensor.h"
#include "volume/volume.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

TEST(PipelineOptions, ImpossibleVolumesAreRefusedByName) {
  volume::VolumeOptions o;
  o.voxel_m = 0;
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.voxel_m", "between 0.001 and 1 metre"});
  o = {};
  o.voxel_m = std::nanf("");
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.voxel_m"});
  o = {};
  o.truncation_voxels = 1e6f;
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.truncation_voxels", "64"});
  o = {};
  o.max_memory_mb = 1e308;
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.max_memory_mb"});
  o = {};
  o.gpu_memory_mb = 2;  // too small for any view's bricks
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.gpu_memory_mb", "4 MiB"});
  o.gpu_memory_mb = 0;  // no GPU budget
  o.Check();
  EXPECT_EQ(o.gpu_bricks(), 0u);
  o.gpu_memory_mb = 8;
  EXPECT_EQ(o.gpu_bricks(), std::size_t(8.0 * (1 << 20) / (double(o.brick_bytes()) + 48)));
  pipeline::PipelineOptions po;
  po.pcf = 7;
  test::ExpectErrorContaining([&] { po.Check(); }, {"'pcf'"});
  SensorInfo no_response = sim::BuiltinXtionProfile();
  no_response.response.reset();
  test::ExpectErrorContaining([&] { pipeline::Pipeline p({}, sim::SimCamera(32, 24), no_response); },
                              {"response", "--response srgb"});
}

}  // namespace
}  // namespace hdrf

namespace hdrf::pipeline {
namespace {

std::vector<FrameInput> Inputs(int n) {
  std::vector<FrameInput> in;
  for (const sim::SimFrame& f : test::Frames(n, sim::AeMode::kFlicker)) {
    FrameInput i;
    i.color = f.color.Clone();
    i.depth_m = test::Metres(f.depth);
    i.timestamp = f.timestamp;
    i.exposure_ms = f.exposure_ms;
    in.push_back(std::move(i));
  }
  return in;
}

// The scan session owns what a scan accumulates: its totals are the sums of its reports,
// its trajectory their poses, and the reference is the ray cast from the last pose (frame to
// model) or the last tracked frame (the brightness-constancy tracker, always frame to frame).
TEST(ScanSession, OwnsTheTrajectoryReportsAndTimings) {
  const auto frames = Inputs(6);
  PipelineOptions o;
  o.volume.voxel_m = 0.047f;
  ScanSession s(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  for (const auto& f : frames) s.Process(f);
  ASSERT_EQ(s.frames(), 6);
  ASSERT_EQ(s.poses().size(), 6u);
  StageTimes sum;
  for (const auto& r : s.reports()) sum += r.ms;
  EXPECT_DOUBLE_EQ(s.total_ms().total(), sum.total());
  EXPECT_NEAR(s.mean_ms().track, sum.track / 6, 1e-12);
  EXPECT_GT(s.frames_per_second(), 0);
  EXPECT_EQ(s.timestamps()[5], frames[5].timestamp);
  ASSERT_TRUE(s.exposure_median_relative_error().has_value());
  EXPECT_LT(*s.exposure_median_relative_error(), 0.05);
  Pipeline& p = s.pipeline();
  EXPECT_TRUE(p.backend().HasReference());
  EXPECT_TRUE(p.backend().ReferencePose().isApprox(p.pose()));
  const FrameViews v = p.DownloadViews();
  EXPECT_EQ(v.radiance.width(), 320);
  EXPECT_EQ(v.render.depth.height(), 240);
  const VolumeStats st = p.volume_stats();
  EXPECT_EQ(st.allocated_bricks, s.reports().back().allocated_bricks);
  EXPECT_GT(st.bytes, 0u);

  o.tracker.kind = tracking::TrackerKind::kIntensity;
  ScanSession base(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  for (int i = 0; i < 3; ++i) base.Process(frames[std::size_t(i)]);
  EXPECT_TRUE(base.pipeline().backend().ReferencePose().isApprox(base.poses().back()));
}

// The CPU engine gives the same trajectory on every run (its reductions add the threads'
// partial sums in a fixed order).
TEST(ScanSession, RunsAreReproducible) {
  const auto frames = Inputs(8);
  PipelineOptions o;
  o.volume.voxel_m = 0.047f;
  ScanSession a(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  ScanSession b(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  for (const auto& f : frames) a.Process(f), b.Process(f);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(a.poses()[std::size_t(i)].matrix(), b.poses()[std::size_t(i)].matrix()) << "frame " << i;
    EXPECT_EQ(a.reports()[std::size_t(i)].exposure_ratio, b.reports()[std::size_t(i)].exposure_ratio);
  }
}

}  // namespace
}  // namespace hdrf::pipeline
