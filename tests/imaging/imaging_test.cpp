#include <gtest/gtest.h>

#include <limits>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "imaging/imaging.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

// Depths of kilometres beside metres (a wrong depth scale), and infinite ones: the range
// weight's bin stays in its table, neighbours that far apart get the last bin's weight.
TEST(Imaging, BilateralFilterTakesAbsurdDepthsWithoutLeavingItsTable) {
  DepthImage d(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) d(x, y) = (x + y) % 2 ? 3.0e6f : 1.f;
  d(3, 3) = std::numeric_limits<float>::infinity();
  const DepthImage f = imaging::BilateralDepth(d);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const float want = x == 3 && y == 3 ? 0.f : (x + y) % 2 ? 3.0e6f : 1.f;  // infinite: no depth
      EXPECT_NEAR(f(x, y), want, 1e-3 * want + 1e-6) << x << "," << y;
    }
}

TEST(Imaging, BilateralFilterSmoothsNoiseAndKeepsDepthEdges) {
  // A 1 m / 2 m step with 1 cm noise and a hole.
  DepthImage d(64, 48);
  std::uint32_t h = 12345;
  auto noise = [&h] {
    h = h * 1664525u + 1013904223u;
    return (float((h >> 8) & 0xffff) / 65535.f - 0.5f) * 0.0346f;  // uniform, sd 1 cm
  };
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) d(x, y) = (x < 32 ? 1.f : 2.f) + noise();
  d(10, 10) = 0;
  const DepthImage f = imaging::BilateralDepth(d);
  double in2 = 0, out2 = 0;
  int n = 0;
  float worst_edge = 0;
  for (int y = 4; y < 44; ++y)
    for (int x = 4; x < 60; ++x) {
      const float truth = x < 32 ? 1.f : 2.f;
      if (x >= 30 && x <= 33) worst_edge = std::max(worst_edge, std::abs(f(x, y) - truth));
      if (d(x, y) == 0) continue;
      in2 += std::pow(d(x, y) - truth, 2);
      out2 += std::pow(f(x, y) - truth, 2);
      ++n;
    }
  std::printf("bilateral: noise %.4f -> %.4f m; worst error next to the edge %.4f m\n", std::sqrt(in2 / n),
              std::sqrt(out2 / n), worst_edge);
  EXPECT_LT(std::sqrt(out2 / n), 0.5 * std::sqrt(in2 / n));
  EXPECT_LT(worst_edge, 0.03f);  // no blending across the 1 m step
  EXPECT_EQ(f(10, 10), 0.f);     // holes stay holes
}

}  // namespace
}  // namespace hdrf

namespace hdrf::imaging {
namespace {

// Vertices back-project the depth; normals of a plane facing the camera point at it and are
// undefined across a depth jump; depth pyramids average only neighbours close in depth.
TEST(ImagingSteps, VerticesNormalsAndDepthPyramid) {
  const PinholeCamera cam{4, 4, 2.f, 2.f, 1.5f, 1.5f};
  DepthImage d(4, 4, 2.f);
  const Float3 v = VertexPixel(View(d), cam, 3, 1);
  EXPECT_FLOAT_EQ(v.x, (3 - 1.5f) * 2.f / 2.f);
  EXPECT_FLOAT_EQ(v.y, (1 - 1.5f) * 2.f / 2.f);
  EXPECT_FLOAT_EQ(v.z, 2.f);
  Image<Float3> vm(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) vm(x, y) = VertexPixel(View(d), cam, x, y);
  const Float3 n = NormalPixel(View(vm), 0.1f, 1, 1);
  EXPECT_NEAR(n.z, -1.f, 1e-6);
  EXPECT_NEAR(n.x, 0.f, 1e-6);
  vm(2, 1).z = 3.f;  // a jump of 50 %
  EXPECT_EQ(Length(NormalPixel(View(vm), 0.1f, 1, 1)), 0.f);
  EXPECT_GT(Length(NormalPixel(View(vm), 0.6f, 1, 1)), 0.f);
  EXPECT_EQ(Length(NormalPixel(View(vm), 0.1f, 3, 3)), 0.f);  // no right neighbour
  DepthImage p(2, 2);
  p(0, 0) = 1.f, p(1, 0) = 1.02f, p(0, 1) = 0.f, p(1, 1) = 3.f;
  EXPECT_FLOAT_EQ(DownsampleDepthPixel(View(p), 0, 0), 1.01f);  // the far and empty ones left out
  p(0, 0) = 0.f;
  EXPECT_EQ(DownsampleDepthPixel(View(p), 0, 0), 0.f);  // no data at the sample stays none
}

// The CPU's ways for pixels whose window lies inside the image (rows read without border
// checks, four pixels of a row at once) give the bits of the border-checked taps, written
// out here as the GPU takes them, on a sensor frame with holes, edges and invalid depths
// (none, negative, not finite, beyond the float range the filter takes), for each radius.
TEST(Imaging, BilateralFilterInsideTheImageGivesTheBorderCheckedBits) {
  const auto frames = Frames(1, sim::AeMode::kFixed);
  DepthImage d = Metres(frames[0].depth);
  std::uint32_t h = 99;
  for (int k = 0; k < 2000; ++k) {  // holes and non-finite depths scattered through
    h = h * 1664525u + 1013904223u;
    const float odd[5] = {std::numeric_limits<float>::quiet_NaN(), 0.f, std::numeric_limits<float>::infinity(), -1.f, 3.2e38f};
    d[std::size_t(h >> 8) % d.size()] = odd[k % 5];
  }
  long differ = 0, inside = 0;
  for (int r : {1, 3, 5}) {
    const imaging::BilateralTables t = imaging::MakeBilateralTables(2.f, 0.05f, r);
    const DepthImage f = imaging::BilateralDepth(d, 2.f, 0.05f, r);
    const int side = 2 * r + 1;
    for (int y = 0; y < d.height(); ++y)
      for (int x = 0; x < d.width(); ++x) {
        const float c = d(x, y);
        float want = 0.f;
        if (c > 0.f && c <= 3.0e38f) {
          float sw = 0.f, sv = 0.f;
          for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx) {
              const int xx = x + dx, yy = y + dy;
              if (xx < 0 || yy < 0 || xx >= d.width() || yy >= d.height()) continue;
              const float v = d(xx, yy);
              if (!(v > 0.f && v <= 3.0e38f)) continue;
              const float fb = std::fabs(v - c) * t.to_bin;
              const int bin = fb < float(imaging::kBilateralBins) ? int(fb) : imaging::kBilateralBins;
              const float wgt = t.spatial[(dy + r) * side + dx + r] * t.range[bin];
              sw += wgt;
              sv += wgt * v;
            }
          want = sv / sw;
          inside += x >= r && y >= r && x + r < d.width() && y + r < d.height();
        }
        differ += std::memcmp(&want, &f(x, y), sizeof want) != 0;
      }
  }
  std::printf("bilateral: %ld filtered pixels inside the image, %ld differ\n", inside, differ);
  EXPECT_GT(inside, 100000);
  EXPECT_EQ(differ, 0);
}

}  // namespace
}  // namespace hdrf::imaging
