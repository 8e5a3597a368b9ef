// The evaluation's baseline trackers (NCC, joint exposure) and the experiment's error
// bookkeeping, against the synthetic sensor's ground truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "baseline_trackers.h"
#include "tracking_experiment.h"
#include "pipeline/frame_source.h"
#include "sim/synthetic_source.h"

namespace hdrf {
namespace {

std::vector<pipeline::FrameInput> Read(int n, sim::AeMode ae) {
  sim::SimOptions o;
  o.frames = n;
  o.ae.mode = ae;
  pipeline::SyntheticFrameSource src(o);
  return pipeline::ReadAll(src);
}

std::vector<Pose> Truth(const std::vector<pipeline::FrameInput>& f) {
  std::vector<Pose> t;
  for (const auto& x : f) t.push_back(f[0].T_world_camera_true->inverse() * *x.T_world_camera_true);
  return t;
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Meilland-style joint estimation: through flicker the gain it finds is the ratio of the
// exposures the sensor reports, and the camera is followed, for exposure changes of up to
// two stops. (Larger drops from a long exposure defeat it: the reference's trusted pixels
// are the dark ones, nearly black in the short exposure; docs/results/tracking.md.)
TEST(Baselines, JointExposureRecoversTheExposureRatioAndThePose) {
  const auto frames = Read(40, sim::AeMode::kFlicker);
  const auto truth = Truth(frames);
  const SensorInfo s = sim::SyntheticSource(sim::SimOptions{}).sensor();
  experiments::BaselineTracker t(experiments::BaselineKind::kJointExposure, s.camera, s);
  std::vector<Pose> est;
  std::vector<double> rel, rel_small, rpe_small;
  int lost = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const experiments::BaselineStep st = t.Process(frames[i].color, frames[i].depth_m);
    est.push_back(st.T_world_camera);
    lost += st.lost;
    if (i == 0) continue;
    const double ratio = *frames[i - 1].exposure_ms / *frames[i].exposure_ms;
    rel.push_back(std::abs(st.gain / ratio - 1));
    if (std::abs(std::log2(ratio)) <= 2.0) {
      rel_small.push_back(rel.back());
      const Pose d = (truth[i - 1].inverse() * truth[i]).inverse() * (est[i - 1].inverse() * est[i]);
      rpe_small.push_back(se3::TranslationNorm(d));
    }
  }
  std::printf("joint exposure, 40 flicker frames: gain median error %.2f %%; jumps <= 2 stops (%zu): gain max "
              "error %.1f %%, frame-to-frame error max %.1f mm\n",
              100 * Median(rel), rel_small.size(), 100 * *std::max_element(rel_small.begin(), rel_small.end()),
              1000 * *std::max_element(rpe_small.begin(), rpe_small.end()));
  EXPECT_EQ(lost, 0);
  EXPECT_LT(Median(rel), 0.03);
  ASSERT_GE(rel_small.size(), 20u);
  EXPECT_LT(Median(rel_small), 0.02);
  EXPECT_LT(*std::max_element(rel_small.begin(), rel_small.end()), 0.15);
  EXPECT_LT(*std::max_element(rpe_small.begin(), rpe_small.end()), 0.01);
}

// NCC on raw intensity at a fixed exposure tracks (its home ground); the brightness changes
// of flicker are what it is meant to absorb too.
TEST(Baselines, NccTracksAtAFixedExposure) {
  const auto frames = Read(40, sim::AeMode::kFixed);
  const SensorInfo s = sim::SyntheticSource(sim::SimOptions{}).sensor();
  experiments::BaselineTracker t(experiments::BaselineKind::kNcc, s.camera, s);
  std::vector<Pose> est;
  for (const auto& f : frames) est.push_back(t.Process(f.color, f.depth_m).T_world_camera);
  const auto e = eval::CompareTrajectories(est, Truth(frames));
  std::printf("NCC, 40 fixed-exposure frames: ATE %.2f cm, RPE %.2f mm\n", 100 * e.ate_rmse_m,
              1000 * e.rpe_trans_rmse_m);
  EXPECT_LT(e.ate_rmse_m, 0.02);
}

TEST(Baselines, JointExposureNeedsAResponse) {
  SensorInfo s = sim::SyntheticSource(sim::SimOptions{}).sensor();
  s.response.reset();
  EXPECT_THROW(experiments::BaselineTracker(experiments::BaselineKind::kJointExposure, s.camera, s), Error);
}

// Per-frame errors: a trajectory offset by a rigid transform has none after the alignment;
// a known error in one frame shows up in that frame only.
TEST(Experiment, PerFrameErrorsLocateAKnownError) {
  std::vector<Pose> gt, est;
  Vec6 off;
  off << 0.2, 0.1, -0.3, 0.05, 0.1, -0.2;
  for (int i = 0; i < 30; ++i) {
    Vec6 xi;
    xi << 0.02 * i, std::sin(0.2 * i), 0.01 * i, 0.0, 0.01 * i, 0.0;
    gt.push_back(se3::Exp(xi));
    est.push_back(se3::Exp(off) * gt.back());
  }
  Vec6 rot = Vec6::Zero();
  rot(3) = 2.0 * M_PI / 180.0;
  est[7] = est[7] * se3::Exp(rot);  // 2 degrees wrong in frame 7
  const auto e = eval::CompareTrajectories(est, gt);
  const auto pf = experiments::PerFrameErrors(est, gt, e.T_gt_est);
  ASSERT_EQ(pf.rot_deg.size(), 30u);
  EXPECT_NEAR(pf.rot_deg[7], 2.0, 0.05);
  for (int i = 0; i < 30; ++i)
    if (i != 7) {
      EXPECT_LT(pf.rot_deg[std::size_t(i)], 0.05) << i;
      EXPECT_LT(pf.trans_m[std::size_t(i)], 1e-6) << i;
    }
}

// The experiment's runner: the engine tracker through its Pipeline, a baseline through its
// own loop; both give one pose per frame and a time.
TEST(Experiment, RunnerGivesOnePosePerFrame) {
  const auto frames = Read(12, sim::AeMode::kFlicker);
  const SensorInfo s = sim::SyntheticSource(sim::SimOptions{}).sensor();
  const auto specs = experiments::ExperimentTrackers();
  ASSERT_EQ(specs.size(), 7u);
  for (const auto& spec : {specs[2], specs[6]}) {
    int calls = 0;
    const auto run = experiments::RunTracker(spec, frames, s.camera, s, pipeline::PipelineOptions{}, [&](int) { ++calls; });
    EXPECT_EQ(run.poses.size(), frames.size()) << spec.id;
    EXPECT_EQ(calls, int(frames.size())) << spec.id;
    EXPECT_GT(run.seconds, 0) << spec.id;
    EXPECT_LT(eval::CompareTrajectories(run.poses, Truth(frames)).ate_rmse_m, 0.03) << spec.id;
  }
}

}  // namespace
}  // namespace hdrf
