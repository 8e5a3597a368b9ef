// The one Reinhard definition (core/tonemap) that the reports, the PLY colours and the
// studio's views share.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tonemap/display.h"

namespace hdrf::tonemap {
namespace {

TEST(Reinhard, PixelCurveAndLogAverage) {
  const Float3 grey = ReinhardPixel({1.f, 1.f, 1.f});  // luminance 1 -> 1 / (1 + 1)
  EXPECT_NEAR(grey.x, 0.5f, 1e-6);
  EXPECT_NEAR(grey.z, 0.5f, 1e-6);
  const Float3 red = ReinhardPixel({3.f, 0.f, 0.f});  // colour ratios kept
  EXPECT_EQ(red.y, 0.f);
  EXPECT_NEAR(red.x, 3.f / (1.f + 3.f * 0.2126f), 1e-5);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(ReinhardPixel({nan, 1.f, 1.f}).y, 0.f);
  EXPECT_EQ(ReinhardPixel({-1.f, -1.f, -1.f}).x, 0.f);
  const std::vector<Float3> px = {{0, 0, 0}, {4, 4, 4}, {0.25f, 0.25f, 0.25f}, {nan, nan, nan}};
  EXPECT_NEAR(LogAverageLuminance(px.data(), px.size()), 1.f, 1e-5);  // sqrt(4 * 0.25); the rest left out
  EXPECT_EQ(LogAverageLuminance(px.data(), 1), 1.f);                   // none usable
  // The image operator maps the log-average to the key: a uniform image at any level gives
  // the same display value.
  RadianceImage dim(2, 2, Float3{0.01f, 0.01f, 0.01f}), bright(2, 2, Float3{50.f, 50.f, 50.f});
  EXPECT_EQ(Reinhard(dim)[0].r, Reinhard(bright)[0].r);
}

}  // namespace
}  // namespace hdrf::tonemap
