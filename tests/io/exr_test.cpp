#include <gtest/gtest.h>

#include <cmath>

#include "io/exr.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

using test::ExpectErrorContaining;
using test::TempDir;

RadianceImage HdrRamp() {
  RadianceImage img(16, 9);
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 16; ++x) {
      const float v = std::pow(10.f, float(x) * 0.5f - 3.f);  // 1e-3 .. 3e4: a wide HDR range
      img(x, y) = {v, v * 0.5f + float(y), v * 2.f};
    }
  return img;
}

TEST(Exr, FloatRoundTripIsBitExact) {
  TempDir dir;
  const RadianceImage img = HdrRamp();
  WriteExr(dir / "f.exr", img, ExrPrecision::kFloat);
  const RadianceImage back = ReadExr(dir / "f.exr");
  ASSERT_EQ(back.width(), 16);
  ASSERT_EQ(back.height(), 9);
  for (std::size_t i = 0; i < img.size(); ++i) {
    ASSERT_EQ(back[i].x, img[i].x);
    ASSERT_EQ(back[i].y, img[i].y);
    ASSERT_EQ(back[i].z, img[i].z);
  }
}

TEST(Exr, HalfRoundTripWithinHalfPrecision) {
  TempDir dir;
  const RadianceImage img = HdrRamp();
  WriteExr(dir / "h.exr", img, ExrPrecision::kHalf);
  const RadianceImage back = ReadExr(dir / "h.exr");
  double worst = 0;
  for (std::size_t i = 0; i < img.size(); ++i)
    worst = std::max(worst, std::abs(double(back[i].x) - img[i].x) / img[i].x);
  EXPECT_LT(worst, 1.0 / 1024);  // half has a 10-bit mantissa
  EXPECT_GT(worst, 0.0);         // and really is half, not float
  EXPECT_LT(std::filesystem::file_size(dir / "h.exr"), 16u * 9u * 12u + 2000u);
}

TEST(Exr, MissingAndNonExrNamed) {
  TempDir dir;
  ExpectErrorContaining([&] { ReadExr(dir / "none.exr"); }, {"none.exr", "missing"});
  test::WriteText(dir / "bad.exr", "not an exr at all");
  ExpectErrorContaining([&] { ReadExr(dir / "bad.exr"); }, {"bad.exr", "OpenEXR"});
}

TEST(Exr, NaNPixelsRejected) {
  TempDir dir;
  RadianceImage img = HdrRamp();
  img(3, 4).y = std::nanf("");
  WriteExr(dir / "n.exr", img, ExrPrecision::kFloat);
  ExpectErrorContaining([&] { ReadExr(dir / "n.exr"); }, {"n.exr", "1 pixel(s)", "NaN"});
}

TEST(Exr, ReadsRealHalfFloatPizImage) {
  const auto p = test::SharedData("hdr_images/Desk.exr");
  HDRF_SKIP_WITHOUT(p, "hdr_images/Desk.exr");
  const RadianceImage img = ReadExr(p);
  EXPECT_EQ(img.width(), 644);
  EXPECT_EQ(img.height(), 874);
  float hi = 0;
  for (std::size_t i = 0; i < img.size(); ++i) hi = std::max(hi, img[i].y);
  EXPECT_GT(hi, 100.f);  // bright stained-glass window (its 99.9th percentile is about 138)
}

}  // namespace
}  // namespace hdrf::io
