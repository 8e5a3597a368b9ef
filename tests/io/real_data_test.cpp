// Real RGB-D frames from the shared data folder (../shared/data); skipped where absent.
#include <gtest/gtest.h>

#include <fstream>

#include "io/image_io.h"
#include "io/sequence.h"
#include "io/sequence_summary.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

namespace fs = std::filesystem;

TEST(RealData, SevenScenesFramesDecode) {
  const auto dir = test::SharedData("7scenes_redkitchen/frames");
  HDRF_SKIP_WITHOUT(dir, "7scenes_redkitchen");
  const ColorImage c = ReadColorImage(dir / "frame-000150.color.png");
  EXPECT_EQ(c.width(), 640);
  EXPECT_EQ(c.height(), 480);
  double mean = 0;
  for (std::size_t i = 0; i < c.size(); ++i) mean += (c[i].r + c[i].g + c[i].b) / 3.0;
  mean /= double(c.size());
  EXPECT_GT(mean, 100.0);  // the recording: mean grey 114.9 .. 125.2 over the 50 frames
  EXPECT_LT(mean, 135.0);
  const DepthImage d = DepthToMetres(ReadDepthImage(dir / "frame-000150.depth.png"), 1000.0);
  std::size_t valid = 0;
  float lo = 1e9f, hi = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] > 0 && d[i] < 65.0f) {
      ++valid;
      lo = std::min(lo, d[i]);
      hi = std::max(hi, d[i]);
    }
  const double coverage = double(valid) / double(d.size());
  EXPECT_GT(coverage, 0.85);  // the recording has 7.6 .. 13.7 % invalid depth
  EXPECT_LT(coverage, 0.93);
  EXPECT_GT(lo, 0.9f);
  EXPECT_LT(hi, 3.0f);
}

// The 7-Scenes frames arranged in the TUM layout (as a user converting them would), read
// through SequenceReader and summarised as `hdrfusion info` does.
TEST(RealData, SevenScenesAsTumSequence) {
  const auto src = test::SharedData("7scenes_redkitchen/frames");
  HDRF_SKIP_WITHOUT(src, "7scenes_redkitchen");
  test::TempDir dir;
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  std::string rgb = "# colour\n", depth = "# depth\n";
  for (int k = 150; k < 160; ++k) {
    const std::string n = "frame-000" + std::to_string(k);
    const std::string t = std::to_string(k / 30.0);
    fs::copy_file(src / (n + ".color.png"), dir / "rgb" / (n + ".png"));
    fs::copy_file(src / (n + ".depth.png"), dir / "depth" / (n + ".png"));
    rgb += t + " rgb/" + n + ".png\n";
    depth += t + " depth/" + n + ".png\n";
  }
  test::WriteText(dir / "rgb.txt", rgb);
  test::WriteText(dir / "depth.txt", depth);
  test::WriteText(dir / "sensor.json",
                  R"({"camera": {"width": 640, "height": 480, "fx": 585, "fy": 585, "cx": 320,
                      "cy": 240}, "depth": {"scale": 1000}})");
  const SequenceReader seq(dir.path());
  ASSERT_EQ(seq.size(), 10u);
  const SequenceSummary s = Summarize(seq, 10);
  EXPECT_NEAR(s.rate_hz, 30.0, 0.01);
  EXPECT_GT(s.depth_coverage, 0.85);
  EXPECT_LT(s.depth_coverage, 0.93);
  EXPECT_GT(s.depth_min_m, 0.9);
  EXPECT_LT(s.depth_max_m, 3.0);
}

TEST(RealData, TumKinectFrameDepthRange) {
  const auto p = test::SharedData("open3d_rgbd/other_formats/TUM_depth.png");
  HDRF_SKIP_WITHOUT(p, "open3d_rgbd/other_formats");
  const DepthImage d = DepthToMetres(ReadDepthImage(p), 5000.0);
  std::size_t zeros = 0;
  float lo = 1e9f, hi = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (d[i] == 0) {
      ++zeros;
      continue;
    }
    lo = std::min(lo, d[i]);
    hi = std::max(hi, d[i]);
  }
  EXPECT_NEAR(double(zeros) / double(d.size()), 0.19, 0.02);  // the recording: 19 % zeros
  EXPECT_NEAR(lo, 1.46, 0.02);
  EXPECT_NEAR(hi, 9.3, 0.1);
}

}  // namespace
}  // namespace hdrf::io
