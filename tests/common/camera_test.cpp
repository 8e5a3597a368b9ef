#include <gtest/gtest.h>

#include "common/camera.h"

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

}  // namespace
}  // namespace hdrf
