#include <gtest/gtest.h>

#include <vector>

#include "common/error.h"
#include "radiometry/radiance.h"
#include "radiometry/radiance_impl.h"
#include "support/test_support.h"

namespace hdrf::radiometry {
namespace {

// One pixel: radiance through the tables, confidence the mean and the largest of the
// channels' PCF, none for a clipped or black channel.
TEST(Radiance, PixelConfidenceIsTheMeanAndMaxOfUnclippedChannels) {
  std::vector<float> inv(768), pcf(768);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) {
      inv[std::size_t(c * 256 + i)] = 0.01f * float(i) * float(c + 1);
      pcf[std::size_t(c * 256 + i)] = 0.1f * float(c + 1);
    }
  Float3 r;
  float mean = 0, mx = 0;
  ConvertPixel({10, 20, 30}, inv.data(), pcf.data(), &r, &mean, &mx);
  EXPECT_FLOAT_EQ(r.x, 0.1f);
  EXPECT_FLOAT_EQ(r.z, 0.01f * 30.f * 3.f);
  EXPECT_FLOAT_EQ(mean, (0.1f + 0.2f + 0.3f) / 3.f);
  EXPECT_FLOAT_EQ(mx, 0.3f);
  ConvertPixel({10, 255, 0}, inv.data(), pcf.data(), &r, &mean, &mx);
  EXPECT_FLOAT_EQ(mean, 0.1f / 3.f);
  EXPECT_FLOAT_EQ(mx, 0.1f);
  EXPECT_FLOAT_EQ(r.y, 0.01f * 255.f * 2.f);  // radiance is still converted
}

TEST(Radiance, InverseResponseDividedByExposure) {
  InverseResponse r;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) r.table[c][i] = float(i) * float(c + 1);
  ColorImage img(3, 2);
  img(0, 0) = {10, 20, 30};
  img(2, 1) = {255, 0, 128};
  RadianceImage out;
  ConvertToRadiance(img, r, 4.0f, out);
  ASSERT_EQ(out.width(), 3);
  ASSERT_EQ(out.height(), 2);
  EXPECT_FLOAT_EQ(out(0, 0).x, 10.f / 4.f);
  EXPECT_FLOAT_EQ(out(0, 0).y, 40.f / 4.f);
  EXPECT_FLOAT_EQ(out(0, 0).z, 90.f / 4.f);
  EXPECT_FLOAT_EQ(out(2, 1).x, 255.f / 4.f);
  EXPECT_FLOAT_EQ(out(2, 1).y, 0.f);
  EXPECT_FLOAT_EQ(out(2, 1).z, 384.f / 4.f);
}

TEST(Radiance, RejectsNonPositiveExposure) {
  ColorImage img(2, 2);
  RadianceImage out;
  test::ExpectErrorContaining(
      [&] { ConvertToRadiance(img, InverseResponse::Srgb(), 0.f, out); }, {"exposure"});
}

TEST(Radiance, CudaRequestWithoutCudaBuildIsAClearError) {
  if (HDRF_HAS_CUDA) GTEST_SKIP() << "this build has the CUDA backend";
  ColorImage img(2, 2);
  RadianceImage out;
  test::ExpectErrorContaining(
      [&] { ConvertToRadiance(img, InverseResponse::Srgb(), 1.f, out, Device::kCuda); },
      {"no CUDA backend", "--device cpu"});
}

}  // namespace
}  // namespace hdrf::radiometry
