// The exposure estimate on the GPU (a digit-by-digit select of the weighted median) against
// the CPU's (sorted) on identical inputs. Skips (with the reason) where no GPU is usable.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "common/cuda_runtime.h"
#include "exposure/exposure.h"
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

// A wall 2 m away seen from the identity pose; the live radiance is the model's over the
// ratio t, times a factor of `levels` values (few levels: many samples share a ratio);
// a share of the pixels have no model surface or no live confidence.
Scene MakeScene(unsigned seed, double t, int levels, double invalid) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::uniform_int_distribution<int> level(0, levels - 1);
  for (int y = 0; y < s.cam.height; ++y)
    for (int x = 0; x < s.cam.width; ++x) {
      s.vertex(x, y) = u(rng) < invalid ? Float3{0, 0, 0} : s.cam.BackProject(float(x), float(y), 2.f);
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
    const Scene s = MakeScene(c.seed, c.t, c.levels, c.invalid);
    ExposureOptions o;
    o.stride = c.stride;
    const ExposureEstimate cpu =
        EstimateExposureRatio(s.vertex, s.model, s.live, s.confidence, s.cam, Pose::Identity(), o);
    const DeviceImage<Float3> v(s.vertex), m(s.model), l(s.live);
    const DeviceImage<float> w(s.confidence);
    GpuExposureEstimator est(s.cam.width, s.cam.height, o);
    const ExposureEstimate gpu = est.Estimate({v.view(), m.view(), l.view(), w.view(), s.cam, ToRigidTransform(Pose::Identity())});
    std::printf("seed %u (t %.2f, %d levels, %.0f%% invalid, stride %d): CPU %ld samples ratio %.9g, GPU %ld "
                "samples ratio %.9g\n",
                c.seed, c.t, c.levels, 100 * c.invalid, c.stride, cpu.samples, cpu.ratio, gpu.samples, gpu.ratio);
    EXPECT_EQ(gpu.samples, cpu.samples) << "seed " << c.seed;
    EXPECT_EQ(gpu.valid, cpu.valid) << "seed " << c.seed;
    EXPECT_NEAR(gpu.ratio, cpu.ratio, 1e-12 * cpu.ratio) << "seed " << c.seed;
    if (c.invalid < 1) {
      EXPECT_TRUE(cpu.valid);
      EXPECT_NEAR(cpu.ratio, c.t, 0.25 * c.t) << "seed " << c.seed;  // the scene's ratio, within its spread
    }
  }
#endif
}

}  // namespace
}  // namespace hdrf::exposure
