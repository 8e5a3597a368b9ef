#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "io/image_io.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

using test::ExpectErrorContaining;
using test::TempDir;

TEST(ImageIo, ColourRoundTripIsLosslessAndRgbOrdered) {
  TempDir dir;
  ColorImage img(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) img(x, y) = {std::uint8_t(x * 30), std::uint8_t(y * 50), 200};
  WriteColorPng(dir / "c.png", img);
  const ColorImage back = ReadColorImage(dir / "c.png");
  ASSERT_EQ(back.width(), 7);
  ASSERT_EQ(back.height(), 5);
  for (std::size_t i = 0; i < img.size(); ++i) ASSERT_EQ(back[i], img[i]) << "pixel " << i;
  // OpenCV writes BGR: pixel (6, 0) red 180 must be the third byte in OpenCV's order.
  const cv::Mat m = cv::imread((dir / "c.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(m.at<cv::Vec3b>(0, 6)[2], 180);
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
}

TEST(ImageIo, DepthRoundTripKeepsAll16Bits) {
  TempDir dir;
  DepthRawImage d(4, 3);
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::uint16_t(i * 5461 + 1);
  d[5] = 65535;
  WriteDepthPng(dir / "d.png", d);
  const DepthRawImage back = ReadDepthImage(dir / "d.png");
  for (std::size_t i = 0; i < d.size(); ++i) ASSERT_EQ(back[i], d[i]);
  const DepthImage m = DepthToMetres(back, 5000.0);
  EXPECT_FLOAT_EQ(m[1], 5462.f / 5000.f);
  // 65535 is the sensors' and datasets' "no depth" (as 0 is), not a surface 13 m away.
  EXPECT_EQ(m[5], 0.f);
  const DepthRawImage again = DepthFromMetres(m, 5000.0);
  for (std::size_t i = 0; i < d.size(); ++i) ASSERT_EQ(again[i], i == 5 ? 0 : d[i]) << "pixel " << i;
  // A depth beyond the largest code is written as the largest valid one, never as "no depth".
  DepthImage far(1, 1);
  far[0] = 100.f;
  EXPECT_EQ(DepthFromMetres(far, 5000.0)[0], 65534);
}

TEST(ImageIo, WrongBitDepthAndChannelsNameTheFile) {
  TempDir dir;
  cv::imwrite((dir / "depth8.png").string(), cv::Mat(3, 3, CV_8UC1, cv::Scalar(9)));
  ExpectErrorContaining([&] { ReadDepthImage(dir / "depth8.png"); },
                        {"depth8.png", "16-bit", "found 8-bit"});
  cv::imwrite((dir / "color16.png").string(), cv::Mat(3, 3, CV_16UC3, cv::Scalar(9, 9, 9)));
  ExpectErrorContaining([&] { ReadColorImage(dir / "color16.png"); },
                        {"color16.png", "8-bit", "found 16-bit"});
  cv::imwrite((dir / "grey.png").string(), cv::Mat(3, 3, CV_8UC1, cv::Scalar(9)));
  ExpectErrorContaining([&] { ReadColorImage(dir / "grey.png"); }, {"grey.png", "3 channels"});
  cv::imwrite((dir / "rgbdepth.png").string(), cv::Mat(3, 3, CV_16UC3, cv::Scalar(1, 2, 3)));
  ExpectErrorContaining([&] { ReadDepthImage(dir / "rgbdepth.png"); },
                        {"rgbdepth.png", "1 channel"});
}

TEST(ImageIo, MissingAndCorruptFilesNamed) {
  TempDir dir;
  ExpectErrorContaining([&] { ReadColorImage(dir / "none.png"); }, {"none.png", "missing"});
  test::WriteText(dir / "bad.png", "\x89PNG\r\n\x1a\nthis is not a png");
  ExpectErrorContaining([&] { ReadColorImage(dir / "bad.png"); }, {"bad.png", "decoded"});
  // An empty file: said so, not OpenCV's assertion on an empty buffer.
  test::WriteText(dir / "empty.png", "");
  for (const auto& read : std::vector<std::function<void()>>{[&] { ReadColorImage(dir / "empty.png"); },
                                                              [&] { ReadDepthImage(dir / "empty.png"); }}) {
    try {
      read();
      ADD_FAILURE() << "an empty file was read as an image";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("empty.png: is empty (0 bytes), not an image"), std::string::npos) << what;
      EXPECT_EQ(what.find("Assertion"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace hdrf::io
