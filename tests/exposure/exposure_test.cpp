#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>

#include "common/error.h"
#include "common/parallel.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "common/se3.h"
#include "exposure/exposure.h"
#include "pipeline/pipeline.h"
#include "sim/builtin_sensor.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

TEST(Exposure, RatioFromMatchedPixels) {
  const auto frames = Frames(2, sim::AeMode::kList, false, {5, 20});
  const PinholeCamera cam = sim::SimCamera(320, 240);
  pipeline::PipelineOptions po;
  pipeline::Pipeline pipe(po, cam, sim::BuiltinXtionProfile());
  pipeline::FrameReport rep;
  for (const auto& f : frames) {
    pipeline::FrameInput in;
    in.color = f.color.Clone();
    in.depth_m = Metres(f.depth);
    in.exposure_ms = f.exposure_ms;
    rep = pipe.Process(in);
  }
  ASSERT_TRUE(rep.exposure_ratio_reported.has_value());
  EXPECT_DOUBLE_EQ(*rep.exposure_ratio_reported, 0.25);
  std::printf("exposure ratio: estimated %.4f, true 0.25 (%ld samples)\n", rep.exposure_ratio, rep.exposure_samples);
  EXPECT_NEAR(rep.exposure_ratio, 0.25, 0.005);
}

}  // namespace
}  // namespace hdrf

namespace hdrf::exposure {
namespace {

// One sample: a model point seen by the live camera gives log(model / live luminance) and
// the live confidence as its weight; points without model radiance, behind the camera,
// outside the image or on unconfident live pixels give none.
TEST(ExposureSample, PairsAModelPointWithTheLivePixelItProjectsTo) {
  const PinholeCamera cam{4, 4, 2.f, 2.f, 1.5f, 1.5f};
  Image<Float3> vertex(4, 4), model_rad(4, 4), live_rad(4, 4);
  Image<float> conf(4, 4, 0.5f);
  for (std::size_t i = 0; i < live_rad.size(); ++i) live_rad[i] = {1, 1, 1};
  vertex(2, 1) = cam.BackProject(2.f, 1.f, 2.f);  // world = camera frame (identity pose)
  model_rad(2, 1) = {4, 4, 4};
  ExposureArgs a{View(vertex), View(model_rad), View(live_rad), View(conf), cam, ToRigidTransform(Pose::Identity())};
  float lr = 0, w = 0;
  ASSERT_TRUE(ExposureSample(a, 2, 1, &lr, &w));
  EXPECT_NEAR(lr, std::log(4.f), 1e-6);
  EXPECT_FLOAT_EQ(w, 0.5f);
  EXPECT_FALSE(ExposureSample(a, 0, 0, &lr, &w));  // no model vertex there
  conf(2, 1) = 0;
  EXPECT_FALSE(ExposureSample(a, 2, 1, &lr, &w));  // live pixel without confidence
  conf(2, 1) = 0.5f;
  vertex(2, 1) = {0.f, 0.f, -1.f};
  EXPECT_FALSE(ExposureSample(a, 2, 1, &lr, &w));  // behind the camera
}

// The weighted median: the sample where the cumulative weight reaches half; too few samples
// give no estimate.
TEST(ExposureMedian, IsWeightedAndNeedsEnoughSamples) {
  std::vector<std::pair<float, float>> s;
  for (int i = 0; i < 60; ++i) s.emplace_back(std::log(2.f), 1.f);
  for (int i = 0; i < 40; ++i) s.emplace_back(std::log(8.f), 1.f);
  ExposureEstimate e = WeightedMedianRatio(s);
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.ratio, 2.0, 1e-5);
  for (int i = 0; i < 40; ++i) s.emplace_back(std::log(8.f), 1.f);  // now 80 of 140 at 8
  e = WeightedMedianRatio(s);
  EXPECT_NEAR(e.ratio, 8.0, 1e-5);
  std::vector<std::pair<float, float>> few(10, {0.f, 1.f});
  EXPECT_FALSE(WeightedMedianRatio(few).valid);
  EXPECT_TRUE(WeightedMedianRatio(few, 10).valid);
}

// Many samples are sorted in two halves side by side and merged (par::Sort): the same order
// as one std::sort, and so the same median bit for bit, whatever the ties (log ratios and
// weights quantised so that many samples compare equal in one or both).
TEST(ExposureMedian, ManySamplesSortedSideBySideGiveTheOneSortsMedian) {
  std::uint32_t state = 12345;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  for (const int n : {4095, 4096, 4097, 30001, 100000}) {
    std::vector<std::pair<float, float>> s;
    for (int i = 0; i < n; ++i)
      s.emplace_back(float(int(next() % 200) - 100) / 64.f, float(1 + next() % 7) / 8.f);
    std::vector<std::pair<float, float>> halves = s, one = s;
    par::Sort(par::Host{}, halves.begin(), halves.end());
    std::sort(one.begin(), one.end());
    EXPECT_TRUE(halves == one) << n << " samples";
    // The median the one sort gives, summed as WeightedMedianRatio sums.
    double total = 0, acc = 0;
    for (const auto& p : one) total += p.second;
    float want = 0;
    for (const auto& p : one) {
      acc += p.second;
      if (acc >= 0.5 * total) {
        want = p.first;
        break;
      }
    }
    const ExposureEstimate e = WeightedMedianRatio(s);
    ASSERT_TRUE(e.valid);
    EXPECT_EQ(e.samples, n);
    EXPECT_EQ(e.log_ratio, want) << n << " samples";
    EXPECT_EQ(e.ratio, std::exp(double(want))) << n << " samples";
  }
}

}  // namespace
}  // namespace hdrf::exposure
