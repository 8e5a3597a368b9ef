// Runs the real `hdrfusion` binary as a user would and checks exit status and output.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/exr.h"
#include "io/sequence.h"
#include "support/test_support.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string output;
};

Result RunCli(const std::string& args) {
  const std::string cmd = std::string(HDRF_CLI) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  std::array<char, 4096> buf;
  while (pipe && fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  const int raw = pclose(pipe.release());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}

TEST(Cli, InfoReportsASequenceWrittenByAnotherTool) {
  test::TempDir dir;
  const fs::path seq = dir / "seq";
  fs::create_directories(seq / "rgb");
  fs::create_directories(seq / "depth");
  std::string rgb, depth, exposure, gt;
  for (int i = 0; i < 31; ++i) {
    const std::string t = std::to_string(1000.0 + i / 30.0);
    cv::imwrite((seq / "rgb" / (t + ".png")).string(), cv::Mat(12, 16, CV_8UC3, cv::Scalar(50)));
    cv::Mat d(12, 16, CV_16UC1, cv::Scalar(i % 2 ? 0 : 7500));  // every other frame empty
    cv::imwrite((seq / "depth" / (t + ".png")).string(), d);
    rgb += t + " rgb/" + t + ".png\n";
    depth += t + " depth/" + t + ".png\n";
    exposure += t + " " + std::to_string(3 << (i % 4)) + "\n";
    gt += t + " 0 0 " + std::to_string(i * 0.01) + " 0 0 0 1\n";
  }
  test::WriteText(seq / "rgb.txt", rgb);
  test::WriteText(seq / "depth.txt", depth);
  test::WriteText(seq / "exposure.txt", exposure);
  test::WriteText(seq / "groundtruth.txt", gt);
  test::WriteText(seq / "sensor.json",
                  R"({"camera": {"width": 16, "height": 12, "fx": 10, "fy": 10, "cx": 7.5,
                      "cy": 5.5}, "depth": {"scale": 5000}})");
  const Result r = RunCli("info " + seq.string() + " --depth-samples 31");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("frames        31"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1.000 s (30.00 Hz)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("16x12"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 .. 24 ms"), std::string::npos) << r.output;
  // 16 of 31 frames have full depth.
  EXPECT_NE(r.output.find("51.6 % valid pixels, 1.500 .. 1.500 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ground truth  yes (31 of 31 frames)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("response      none"), std::string::npos) << r.output;
}

TEST(Cli, InfoOnBadInputFailsWithOneLineNamingTheFile) {
  test::TempDir dir;
  Result r = RunCli("info " + (dir / "missing").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  test::WriteText(dir / "s" / "sensor.json", "{\"camera\": {}}");
  r = RunCli("info " + (dir / "s").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("sensor.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("camera.width"), std::string::npos) << r.output;
}

TEST(Cli, RadianceRefusesMissingCalibrationAndHonoursSrgbFallback) {
  test::TempDir dir;
  cv::imwrite((dir / "c.png").string(), cv::Mat(4, 4, CV_8UC3, cv::Scalar(0, 0, 255)));
  Result r = RunCli("radiance " + (dir / "c.png").string() + " --out " + (dir / "r.exr").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--response srgb"), std::string::npos) << r.output;
  r = RunCli("radiance " + (dir / "c.png").string() + " --response srgb --exposure 2 --out " +
          (dir / "r.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const RadianceImage img = io::ReadExr(dir / "r.exr");
  EXPECT_FLOAT_EQ(img(2, 2).x, 0.5f);  // red 255 -> 1.0 linear, / 2 ms
  EXPECT_FLOAT_EQ(img(2, 2).z, 0.0f);
}

TEST(Cli, UnknownSubcommandAndMissingArgumentsFail) {
  EXPECT_NE(RunCli("frobnicate").status, 0);
  EXPECT_NE(RunCli("info").status, 0);
  EXPECT_EQ(RunCli("--version").status, 0);
}

}  // namespace
}  // namespace hdrf
