#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "common/camera.h"
#include "common/vec.h"

namespace hdrf {
namespace {

const PinholeCamera kCam{640, 480, 525.f, 520.f, 319.5f, 239.5f};

TEST(PinholeCamera, ProjectInvertsBackProject) {
  for (float v = 0; v < 480; v += 37.3f) {
    for (float u = 0; u < 640; u += 41.7f) {
      const Float3 p = kCam.BackProject(u, v, 2.37f);
      EXPECT_FLOAT_EQ(p.z, 2.37f);
      const Float2 px = kCam.Project(p);
      EXPECT_NEAR(px.x, u, 1e-3);
      EXPECT_NEAR(px.y, v, 1e-3);
    }
  }
}

TEST(PinholeCamera, PrincipalPointProjectsToCentreRay) {
  const Float2 px = kCam.Project({0.f, 0.f, 3.f});
  EXPECT_FLOAT_EQ(px.x, 319.5f);
  EXPECT_FLOAT_EQ(px.y, 239.5f);
}

TEST(PinholeCamera, ScaledCameraMatchesDownsampledPixelCentres) {
  // A point seen at pixel u on the full image is at (u + 0.5) / 2 - 0.5 one level down.
  const PinholeCamera half = kCam.Scaled(2);
  EXPECT_EQ(half.width, 320);
  EXPECT_EQ(half.height, 240);
  const Float3 p{0.31f, -0.22f, 1.7f};
  const Float2 full = kCam.Project(p);
  const Float2 down = half.Project(p);
  EXPECT_NEAR(down.x, (full.x + 0.5f) / 2 - 0.5f, 1e-4);
  EXPECT_NEAR(down.y, (full.y + 0.5f) / 2 - 0.5f, 1e-4);
  const PinholeCamera quarter = kCam.Scaled(4);
  EXPECT_NEAR(quarter.Project(p).x, (full.x + 0.5f) / 4 - 0.5f, 1e-4);
}

TEST(PinholeCamera, ContainsIsInclusiveOfBorderPixels) {
  EXPECT_TRUE(kCam.Contains({0.f, 0.f}));
  EXPECT_TRUE(kCam.Contains({639.f, 479.f}));
  EXPECT_FALSE(kCam.Contains({639.5f, 10.f}));
  EXPECT_FALSE(kCam.Contains({-0.1f, 10.f}));
}

// Floats an inline rounding can meet: halves and whole numbers with the floats next to
// them, both signs, large values, and random bit patterns of floats within +-2e9.
std::vector<float> RoundingProbes() {
  std::vector<float> xs = {0.f, -0.f, 0.5f, -0.5f, 1.5f, -1.5f, 2.5f, -2.5f, 1e9f, -1e9f, 8388607.5f, -8388607.5f,
                           16777217.f, 2147483520.f * 0.999f};
  for (float h = 0.5f; h < 1e6f; h = h * 1.37f + 1.f) {
    const float half = std::floor(h) + 0.5f, whole = std::floor(h) + 1.f;
    for (float x : {half, -half, whole, -whole}) {
      xs.push_back(x);
      xs.push_back(std::nextafter(x, 0.f));
      xs.push_back(std::nextafter(x, 2.f * x));
    }
  }
  std::uint32_t seed = 12345;
  for (int i = 0; i < 200000; ++i) {  // random bit patterns of in-range floats
    seed = seed * 1664525u + 1013904223u;
    float x;
    std::uint32_t bits = seed & 0xcfffffffu;
    std::memcpy(&x, &bits, 4);
    if (std::isfinite(x) && std::fabs(x) < 2e9f) xs.push_back(x);
  }
  return xs;
}

// The inline rounding used for pixel look-ups and voxel storage gives lroundf's integer for
// every float it can meet: halves away from zero, the floats next to each half, large values.
TEST(RoundToInt, MatchesLroundfWhereverTheResultFitsAnInt) {
  const std::vector<float> xs = RoundingProbes();
  int checked = 0;
  for (float x : xs) {
    ASSERT_EQ(RoundToInt(x), int(std::lroundf(x))) << "x = " << x;
    ++checked;
  }
  EXPECT_GT(checked, 150000);
  // Out of range and NaN: a value every bounds test refuses.
  EXPECT_LT(RoundToInt(std::nanf("")), -1000000000);
  EXPECT_LT(RoundToInt(3e9f), -1000000000);
  EXPECT_LT(RoundToInt(-3e9f), -1000000000);
}

// The voxel and brick coordinates' floor (the ray cast's, without the library call) gives
// floorf's integer for the same floats: whole numbers, the floats just below and above them,
// negative fractions (-0.5 -> -1), signed zeros.
TEST(FloorToInt, MatchesFloorfWhereverTheResultFitsAnInt) {
  int checked = 0, negative_fractions = 0;
  for (float x : RoundingProbes()) {
    ASSERT_EQ(FloorToInt(x), int(std::floor(x))) << "x = " << x;
    negative_fractions += x < 0.f && x != std::floor(x);
    ++checked;
  }
  EXPECT_GT(checked, 150000);
  EXPECT_GT(negative_fractions, 1000);
  EXPECT_EQ(FloorToInt(-0.f), 0);
  EXPECT_EQ(FloorToInt(-1e-30f), -1);
  EXPECT_EQ(FloorToInt(std::nextafter(-3.f, 0.f)), -3);
  EXPECT_EQ(FloorToInt(std::nextafter(-3.f, -4.f)), -4);
}

}  // namespace
}  // namespace hdrf
