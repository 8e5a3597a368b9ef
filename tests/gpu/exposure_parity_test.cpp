// The exposure estimate on the GPU (a radix select with exact integer weight sums) against
// the CPU's (sorted) on identical inputs, at poses away from the origin; the selection alone
// on samples chosen to be hard for it; and the estimate queued behind a run, at a pose in
// device memory, against the one made at that pose. Skips (with the reason) where no GPU is
// usable.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/cuda_runtime.h"
#include "common/se3.h"
#include "exposure/exposure.h"
#include "tracking/tracking.h"
#if HDRF_HAS_CUDA
#include "common/device_buffer.h"
#include "exposure/exposure_gpu.h"
#endif

namespace hdrf::exposure {
namespace {

struct Scene {
  PinholeCamera cam{161, 121, 150.f, 150.f, 80.f, 60.f};
  Image<Float3> vertex{cam.width, cam.height};
  RadianceImage model{cam.width, cam.height}, live{cam.width, cam.height};
  Image<float> confidence{cam.width, cam.height};
};

// A wall 2 m away seen from `T` (the model's vertices in the world); the live radiance is
// the model's over the ratio t, times a factor of `levels` values (few levels: many samples
// share a ratio); a share of the pixels have no model surface or no live confidence.
Scene MakeScene(unsigned seed, double t, int levels, double invalid, const Pose& T = Pose::Identity()) {
  Scene s;
  const RigidTransform Tf = ToRigidTransform(T);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::uniform_int_distribution<int> level(0, levels - 1);
  for (int y = 0; y < s.cam.height; ++y)
    for (int x = 0; x < s.cam.width; ++x) {
      s.vertex(x, y) = u(rng) < invalid ? Float3{0, 0, 0} : Tf.Apply(s.cam.BackProject(float(x), float(y), 2.f));
      const Float3 m{0.05f + u(rng), 0.05f + u(rng), 0.05f + u(rng)};
      s.model(x, y) = m;
      const float f = float(std::exp(0.4 * (double(level(rng)) / std::max(1, levels - 1) - 0.5)) / t);
      s.live(x, y) = {m.x * f, m.y * f, m.z * f};
      s.confidence(x, y) = u(rng) < invalid ? 0.f : 0.01f + 0.99f * u(rng);
    }
  return s;
}

TEST(GpuExposureParity, WeightedMedianMatchesTheCpu) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
#if HDRF_HAS_CUDA
  struct Case {
    unsigned seed;
    double t;
    int levels;
    double invalid;
    int stride;
  };
  for (const Case& c : {Case{1, 1.7, 100000, 0.1, 2}, Case{2, 0.4, 5, 0.3, 2}, Case{3, 1.0, 2, 0.0, 1},
                        Case{4, 3.0, 1, 0.5, 3}, Case{5, 1.2, 100000, 1.0, 2}}) {
    // Odd seeds away from the origin (turned and moved: the transform the samples use is
    // made from the pose on each device).
    Vec6 xi;
    xi << 0.7, -1.3, 2.1, 0.3, -0.45, 0.8;
    const Pose T = c.seed % 2 ? se3::Exp(xi * (0.5 + 0.1 * c.seed)) : Pose::Identity();
    const Scene s = MakeScene(c.seed, c.t, c.levels, c.invalid, T);
    ExposureOptions o;
    o.stride = c.stride;
    const ExposureEstimate cpu = EstimateExposureRatio(s.vertex, s.model, s.live, s.confidence, s.cam, T, o);
    const DeviceImage<Float3> v(s.vertex), m(s.model), l(s.live);
    const DeviceImage<float> w(s.confidence);
    GpuExposureEstimator est(s.cam.width, s.cam.height, o);
    const ExposureEstimate gpu = est.Estimate({v.view(), m.view(), l.view(), w.view(), s.cam, {}}, T);
    std::printf("seed %u (t %.2f, %d levels, %.0f%% invalid, stride %d): CPU %ld samples ratio %.9g, GPU %ld "
                "samples ratio %.9g\n",
                c.seed, c.t, c.levels, 100 * c.invalid, c.stride, cpu.samples, cpu.ratio, gpu.samples, gpu.ratio);
    EXPECT_EQ(gpu.samples, cpu.samples) << "seed " << c.seed;
    EXPECT_EQ(gpu.valid, cpu.valid) << "seed " << c.seed;
    EXPECT_NEAR(gpu.ratio, cpu.ratio, 1e-12 * cpu.ratio) << "seed " << c.seed;
    if (cpu.valid) EXPECT_EQ(gpu.log_ratio, cpu.log_ratio) << "seed " << c.seed;  // the same sample
    if (c.invalid < 1) {
      EXPECT_TRUE(cpu.valid);
      EXPECT_NEAR(cpu.ratio, c.t, 0.25 * c.t) << "seed " << c.seed;  // the scene's ratio, within its spread
    }
  }
#endif
}

// The selection alone against the CPU's sorted sum, on samples chosen to catch a wrong bit:
// keys of every sign and magnitude (zeros of both signs, an infinite ratio), many equal keys,
// half the weight reached exactly at a key's last sample, weights from 1e-4 to 1, a few heavy
// samples among many light ones, and too few samples.
TEST(GpuExposureParity, WeightedMedianOfHardSamplesIsTheCpus) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
#if HDRF_HAS_CUDA
  using Samples = std::vector<std::pair<float, float>>;
  std::vector<std::pair<std::string, Samples>> cases;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  {
    Samples s;  // wide keys, both signs (the median a positive key of some magnitude)
    for (int i = 0; i < 200000; ++i) {
      const float mag = std::pow(10.f, -30.f + 60.f * u(rng));
      s.emplace_back(u(rng) < 0.3f ? -mag : mag, 1e-4f + (1.f - 1e-4f) * u(rng));
    }
    s.emplace_back(0.f, 1.f);
    s.emplace_back(-0.f, 1.f);
    s.emplace_back(INFINITY, 1.f);
    cases.emplace_back("wide keys", s);
  }
  {
    Samples s;  // 7 distinct keys, many samples each
    for (int i = 0; i < 100000; ++i) s.emplace_back(0.1f * float(int(7 * u(rng)) - 3), 0.01f + 0.99f * u(rng));
    cases.emplace_back("7 keys", s);
  }
  for (int k = 1; k <= 4; ++k) {
    Samples s;  // weights of 0.25: half the weight reached exactly at the end of a key's run
    for (int i = 0; i < 8 * k; ++i) s.emplace_back(float(i / k) - 3.5f, 0.25f);
    cases.emplace_back("exact half " + std::to_string(k), s);
  }
  {
    Samples s;  // a few heavy samples among light ones
    for (int i = 0; i < 50000; ++i) s.emplace_back(0.5f + 0.01f * u(rng), 1e-4f);
    for (int i = 0; i < 30; ++i) s.emplace_back(-0.2f - 0.01f * float(i), 0.2f);
    cases.emplace_back("heavy few", s);
  }
  {
    Samples s;  // neighbouring floats: keys that differ in the last bit only
    for (int i = 0; i < 4000; ++i) s.emplace_back(i % 2 ? std::nextafter(0.3f, 1.f) : 0.3f, 0.001f + u(rng));
    cases.emplace_back("last bit", s);
  }
  cases.emplace_back("too few", Samples{{0.1f, 1.f}, {0.2f, 1.f}});
  cases.emplace_back("none", Samples{});
  for (auto& [name, samples] : cases) {
    const int min_samples = name == "too few" ? 3 : 1;
    Samples sorted = samples;
    const ExposureEstimate cpu = WeightedMedianRatio(sorted, min_samples);
    const ExposureEstimate gpu = GpuWeightedMedianRatio(samples, min_samples);
    std::printf("%s: %zu samples, CPU %s log ratio %a (ratio %.17g), GPU %s log ratio %a (ratio %.17g)\n",
                name.c_str(), samples.size(), cpu.valid ? "valid" : "invalid", cpu.log_ratio, cpu.ratio,
                gpu.valid ? "valid" : "invalid", gpu.log_ratio, gpu.ratio);
    EXPECT_EQ(gpu.samples, cpu.samples) << name;
    EXPECT_EQ(gpu.valid, cpu.valid) << name;
    if (!cpu.valid) continue;
    EXPECT_EQ(gpu.log_ratio, cpu.log_ratio) << name;  // the same sample's key, bit for bit
    if (std::isfinite(cpu.ratio)) EXPECT_NEAR(gpu.ratio, cpu.ratio, 1e-15 * cpu.ratio) << name;
  }
  EXPECT_FALSE(cases.empty());
#endif
}

// Queued behind other work at a pose in device memory (as behind the tracker's run), the
// estimate is the one made at that pose: the same count and the same ratio, bit for bit.
TEST(GpuExposureParity, QueuedAtADevicePoseIsTheEstimateAtThatPose) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
#if HDRF_HAS_CUDA
  Vec6 xi;
  xi << -0.4, 0.9, 1.6, -0.2, 0.35, -0.6;
  for (const double k : {0.0, 0.3, 1.0}) {
    const Pose T = se3::Exp(k * xi);
    const Scene s = MakeScene(7, 1.45, 100000, 0.2, T);
    const ExposureOptions o;
    const DeviceImage<Float3> v(s.vertex), m(s.model), l(s.live);
    const DeviceImage<float> w(s.confidence);
    const ExposureArgs a{v.view(), m.view(), l.view(), w.view(), s.cam, {}};
    GpuExposureEstimator est(s.cam.width, s.cam.height, o);
    const ExposureEstimate direct = est.Estimate(a, T);
    DeviceBuffer<tracking::PoseD> pose(1);
    const tracking::PoseD p = tracking::ToPoseD(T);
    cuda::CopyHostToDevice(pose.data(), &p, sizeof(p));
    est.Queue(a, pose.data(), nullptr);
    cuda::Synchronize();
    const ExposureEstimate queued = est.Result();
    std::printf("pose %.1f: made %ld samples ratio %.17g, queued %ld samples ratio %.17g\n", k, direct.samples,
                direct.ratio, queued.samples, queued.ratio);
    EXPECT_TRUE(direct.valid);
    EXPECT_GT(direct.samples, 1000);
    EXPECT_NEAR(direct.ratio, 1.45, 0.2);
    EXPECT_EQ(queued.samples, direct.samples);
    EXPECT_EQ(queued.valid, direct.valid);
    EXPECT_EQ(queued.ratio, direct.ratio);  // bit for bit
  }
#endif
}

}  // namespace
}  // namespace hdrf::exposure
