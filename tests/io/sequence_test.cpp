#include <gtest/gtest.h>

#include <cstdio>
#include <vector>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/sequence.h"
#include "io/sequence_source.h"
#include "io/sequence_summary.h"
#include "io/source_spec.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

namespace fs = std::filesystem;
using test::ExpectErrorContaining;
using test::TempDir;
using test::WriteText;

SensorInfo SmallSensor() {
  SensorInfo s;
  s.camera = {8, 6, 7.f, 7.f, 3.5f, 2.5f};
  s.depth_scale = 5000;
  s.response = radiometry::InverseResponse::Srgb();
  return s;
}

ColorImage Pattern(int k) {
  ColorImage c(8, 6);
  for (std::size_t i = 0; i < c.size(); ++i)
    c[i] = {std::uint8_t(i * 3 + k), std::uint8_t(200 - k), std::uint8_t((i * k) & 255)};
  return c;
}

// A TUM-layout sequence written the way the TUM tools and other SLAM software write it:
// OpenCV images, header comments, depth stamped a few ms after colour, no HDR extras.
void WriteForeignSequence(const fs::path& dir, int frames, int width = 8, int height = 6) {
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  std::string rgb = "# color images\n# file: 'rgbd_dataset_freiburg1_xyz.bag'\n# timestamp filename\n";
  std::string depth = "# depth maps\n# file: 'rgbd_dataset_freiburg1_xyz.bag'\n# timestamp filename\n";
  for (int i = 0; i < frames; ++i) {
    char tr[64], td[64];
    std::snprintf(tr, sizeof tr, "1305031102.%06d", 175304 + i * 33333);
    std::snprintf(td, sizeof td, "1305031102.%06d", 175304 + i * 33333 + 7000);
    cv::Mat c(height, width, CV_8UC3, cv::Scalar(10 * i, 20, 30));
    cv::Mat d(height, width, CV_16UC1, cv::Scalar(5000 + 100 * i));
    d.at<std::uint16_t>(0, 0) = 0;  // one hole per frame
    cv::imwrite((dir / "rgb" / (std::string(tr) + ".png")).string(), c);
    cv::imwrite((dir / "depth" / (std::string(td) + ".png")).string(), d);
    rgb += std::string(tr) + " rgb/" + tr + ".png\n";
    depth += std::string(td) + " depth/" + td + ".png\n";
  }
  WriteText(dir / "rgb.txt", rgb);
  WriteText(dir / "depth.txt", depth);
  WriteText(dir / "sensor.json",
            "{\"camera\": {\"width\": " + std::to_string(width) + ", \"height\": " +
                std::to_string(height) +
                ", \"fx\": 517.3, \"fy\": 516.5, \"cx\": 318.6, \"cy\": 255.3},"
                " \"depth\": {\"scale\": 5000}}");
}

TEST(Sequence, WriterReaderRoundTripIsIdentical) {
  TempDir dir;
  const fs::path seq = dir / "seq";
  {
    SequenceWriter w(seq, SmallSensor(), {.write_hdr = true});
    for (int k = 0; k < 5; ++k) {
      DepthRawImage d(8, 6, std::uint16_t(1000 + k));
      RadianceImage hdr(8, 6, Float3{0.5f * k, 1.f, 2.f});
      Vec6 xi;
      xi << 0.1 * k, 0, 0, 0, 0.05 * k, 0;
      w.Add(10.0 + k / 30.0, Pattern(k), &d, 3.0 * (1 << k), se3::Exp(xi), &hdr);
    }
  }
  const SequenceReader r(seq);
  ASSERT_EQ(r.size(), 5u);
  EXPECT_TRUE(r.has_exposure());
  EXPECT_TRUE(r.has_groundtruth());
  EXPECT_TRUE(r.has_hdr());
  ASSERT_TRUE(r.sensor().response.has_value());
  for (int k = 0; k < 5; ++k) {
    const Frame f = r.ReadFrame(k);
    const ColorImage expected = Pattern(k);
    for (std::size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(f.color[i], expected[i]);
    EXPECT_FLOAT_EQ(f.depth_m[3], (1000.f + k) / 5000.f);
    EXPECT_DOUBLE_EQ(*f.info.exposure_ms, 3.0 * (1 << k));
    Vec6 xi;
    xi << 0.1 * k, 0, 0, 0, 0.05 * k, 0;
    EXPECT_LT((f.info.T_world_camera->translation() - se3::Exp(xi).translation()).norm(), 1e-6);
    EXPECT_LT(se3::RotationAngle(f.info.T_world_camera->inverse() * se3::Exp(xi)), 1e-8);
    EXPECT_NEAR(f.info.timestamp, 10.0 + k / 30.0, 1e-6);
    EXPECT_FLOAT_EQ(r.ReadHdr(k)[5].x, 0.5f * k);
  }
}

TEST(Sequence, InterruptedWriterLeavesAValidShorterSequence) {
  TempDir dir;
  auto w = std::make_unique<SequenceWriter>(dir / "s", SmallSensor());
  DepthRawImage d(8, 6, 777);
  for (int k = 0; k < 3; ++k) w->Add(1.0 + k, Pattern(k), &d, 10.0, std::nullopt, nullptr);
  // No destructor, no "finish": read while the writer is still open, as after a crash.
  const SequenceReader r(dir / "s");
  EXPECT_EQ(r.size(), 3u);
  EXPECT_FALSE(r.has_groundtruth());
  w.reset();
}

TEST(Sequence, WriterRefusesNonEmptyFolderAndDecreasingTime) {
  TempDir dir;
  WriteText(dir / "x" / "keep.txt", "precious");
  ExpectErrorContaining([&] { SequenceWriter w(dir / "x", SmallSensor()); },
                        {"x", "not empty"});
  EXPECT_EQ(test::ReadText(dir / "x" / "keep.txt"), "precious");
  SequenceWriter w(dir / "y", SmallSensor());
  w.Add(2.0, Pattern(0), nullptr, std::nullopt, std::nullopt, nullptr);
  ExpectErrorContaining([&] { w.Add(2.0, Pattern(1), nullptr, 1.0, std::nullopt, nullptr); },
                        {"timestamps must increase"});
}

TEST(Sequence, ReadsForeignTumLayoutAndAssociatesDepth) {
  TempDir dir;
  WriteForeignSequence(dir.path(), 12);
  const SequenceReader r(dir.path());
  ASSERT_EQ(r.size(), 12u);
  EXPECT_FALSE(r.has_exposure());
  EXPECT_FALSE(r.has_groundtruth());
  EXPECT_FALSE(r.sensor().response.has_value());
  const Frame f = r.ReadFrame(4);
  EXPECT_EQ(f.color(1, 1).r, 30);  // OpenCV wrote BGR (40, 20, 30): red is 30, blue is 40
  EXPECT_EQ(f.color(1, 1).b, 40);
  EXPECT_FLOAT_EQ(f.depth_m(1, 1), (5000.f + 400.f) / 5000.f);
  EXPECT_EQ(f.depth_m(0, 0), 0.f);
  const SequenceSummary s = Summarize(r);
  EXPECT_EQ(s.frames, 12u);
  EXPECT_NEAR(s.duration_s, 11 * 0.033333, 1e-6);
  EXPECT_NEAR(s.depth_coverage, 47.0 / 48.0, 1e-9);
  EXPECT_NEAR(s.depth_max_m, 1.22, 1e-6);
}

// An exposure list whose stamps match no frame (another recording's, or a clock offset) is
// refused naming it, rather than every frame being taken as of unknown exposure. One stamp
// that matches is enough to read it.
TEST(Sequence, ExposureStampsThatMatchNoFrameAreRefused) {
  TempDir dir;
  WriteForeignSequence(dir.path(), 4);
  WriteText(dir / "exposure.txt", "# timestamp exposure_ms\n1305031902.175304 10\n1305031902.208637 12\n");
  ExpectErrorContaining([&] { SequenceReader r(dir.path()); },
                        {"exposure.txt", "none of its 2 timestamps", "1305031902.175304", "1305031102.175304"});
  WriteText(dir / "exposure.txt", "# timestamp exposure_ms\n1305031102.175304 10\n1305031902.208637 12\n");
  const SequenceReader r(dir.path());
  EXPECT_TRUE(r.has_exposure());
  ASSERT_TRUE(r.frames()[0].exposure_ms.has_value());
  EXPECT_DOUBLE_EQ(*r.frames()[0].exposure_ms, 10.0);
}

// A sequence whose analog gain changes: the scan is told exposure x gain, so doubling the
// gain at half the exposure time reads as the same exposure, not as the light halving.
TEST(Sequence, AnalogGainIsPartOfTheExposureTheScanIsTold) {
  TempDir dir;
  WriteForeignSequence(dir.path(), 3);
  WriteText(dir / "exposure.txt",
            "# timestamp exposure_ms analog_gain\n1305031102.175304 10 1\n1305031102.208637 5 2\n"
            "1305031102.241970 10 4\n");
  SequenceFrameSource src(dir.path());
  pipeline::FrameInput f;
  std::vector<double> e;
  while (src.Next(f)) e.push_back(f.exposure_ms.value_or(-1));
  ASSERT_EQ(e.size(), 3u);
  EXPECT_DOUBLE_EQ(e[0], 10.0);
  EXPECT_DOUBLE_EQ(e[1], 10.0);
  EXPECT_DOUBLE_EQ(e[2], 40.0);
}

TEST(Sequence, SizeMismatchWithSensorJsonNamesTheImage) {
  TempDir dir;
  WriteForeignSequence(dir.path(), 3, 8, 6);
  WriteText(dir / "sensor.json",
            R"({"camera": {"width": 640, "height": 480, "fx": 5, "fy": 5, "cx": 1, "cy": 1},
                "depth": {"scale": 5000}})");
  const SequenceReader r(dir.path());
  ExpectErrorContaining(
      [&] { r.ReadFrame(1); }, {"rgb/1305031102.208637.png", "8x6", "sensor.json says 640x480"});
}

TEST(Sequence, MissingPiecesNamed) {
  TempDir dir;
  ExpectErrorContaining([&] { SequenceReader r(dir / "nope"); }, {"nope", "missing"});
  WriteForeignSequence(dir.path(), 3);
  fs::remove(dir / "depth.txt");
  ExpectErrorContaining([&] { SequenceReader r(dir.path()); }, {"depth.txt", "missing"});
  SequenceReadOptions sweep;
  sweep.allow_missing_depth = true;
  EXPECT_EQ(SequenceReader(dir.path(), sweep).size(), 3u);
  fs::remove(dir / "sensor.json");
  ExpectErrorContaining([&] { SequenceReader r(dir.path()); }, {"sensor.json", "missing"});
}

TEST(Sequence, MissingImageFileNamedWhenRead) {
  TempDir dir;
  WriteForeignSequence(dir.path(), 3);
  fs::remove(dir / "depth" / "1305031102.215637.png");
  const SequenceReader r(dir.path());
  EXPECT_NO_THROW(r.ReadFrame(0));
  ExpectErrorContaining([&] { r.ReadFrame(1); }, {"depth/1305031102.215637.png", "missing"});
}

TEST(Sequence, ColourWithoutDepthIsCountedAndLeftOut) {
  TempDir dir;
  WriteForeignSequence(dir.path(), 4);
  WriteText(dir / "depth.txt",
            "1305031102.182304 depth/1305031102.182304.png\n"
            "1305031102.282304 depth/1305031102.282304.png\n");
  const SequenceReader r(dir.path());
  EXPECT_EQ(r.size(), 2u);
  EXPECT_EQ(r.unmatched_color_frames(), 2u);
}

TEST(Sequence, MalformedExposureAndGroundTruthNamed) {
  TempDir dir;
  WriteForeignSequence(dir.path(), 3);
  WriteText(dir / "exposure.txt", "1305031102.175304 10\n1305031102.208637 abc\n");
  ExpectErrorContaining([&] { SequenceReader r(dir.path()); },
                        {"exposure.txt:2:", "cannot parse exposure_ms"});
  fs::remove(dir / "exposure.txt");
  WriteText(dir / "groundtruth.txt", "1305031102.2 0 0 0 0 0 0 1\n1305031102.1 0 0 0 0 0 0 1\n");
  ExpectErrorContaining([&] { SequenceReader r(dir.path()); },
                        {"groundtruth.txt:2:", "increase"});
}

// A source whose settings are not key=value is refused naming the item, the spec, and a
// spelling that works; settings that are open the synthetic scene at their size.
TEST(SourceSpec, SettingsThatAreNotKeyValueAreRefusedWithAWorkingSpelling) {
  try {
    OpenSource("synthetic:320x240", "");
    ADD_FAILURE() << "synthetic:320x240 was accepted";
  } catch (const SettingError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'320x240' in 'synthetic:320x240' is not key=value"), std::string::npos) << what;
    EXPECT_NE(what.find("(e.g. synthetic:size=320x240,frames=300)"), std::string::npos) << what;
  }
  try {
    SplitSpec("openni:serial", 7);
    ADD_FAILURE() << "openni:serial was accepted";
  } catch (const SettingError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'serial' in 'openni:serial' is not key=value (key=value pairs, separated by commas)"),
              std::string::npos)
        << what;
  }
  const auto source = OpenSource("synthetic:size=160x120,frames=3", "");
  EXPECT_EQ(source->sensor().camera.width, 160);
  EXPECT_EQ(source->sensor().camera.height, 120);
  const auto kv = SplitSpec("synthetic:size=160x120,,frames=3", 10);
  ASSERT_EQ(kv.size(), 2u);
  EXPECT_EQ(kv[1].first, "frames");
  EXPECT_EQ(kv[1].second, "3");
}

}  // namespace
}  // namespace hdrf::io
