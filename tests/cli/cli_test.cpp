// Runs the real `hdrfusion` binary as a user would and checks exit status and output.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/exr.h"
#include "io/sensor_json.h"
#include "io/sequence.h"
#include "support/test_support.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult RunCli(const std::string& args) { return test::RunCommand(std::string(HDRF_CLI) + " " + args); }

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
  const RunResult r = RunCli("info " + seq.string() + " --depth-samples 31");
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
  RunResult r = RunCli("info " + (dir / "missing").string());
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
  RunResult r = RunCli("radiance " + (dir / "c.png").string() + " --out " + (dir / "r.exr").string());
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

namespace hdrf {
namespace {

TEST(Cli, SimulateWritesASequenceThatInfoAndTheReaderAccept) {
  test::TempDir dir;
  const std::string out = (dir / "sim").string();
  RunResult r = RunCli("simulate --out " + out + " --frames 12 --size 64x48 --ae flicker --seed 3");
  ASSERT_EQ(r.status, 0) << r.output;
  const io::SequenceReader seq(out);
  ASSERT_EQ(seq.size(), 12u);
  EXPECT_TRUE(seq.has_exposure() && seq.has_groundtruth() && seq.has_hdr());
  ASSERT_TRUE(seq.sensor().response && seq.sensor().noise);
  EXPECT_EQ(seq.sensor().camera.width, 64);
  EXPECT_NEAR(seq.sensor().noise->sigma_s[1], 0.032663, 1e-6);  // the built-in Xtion profile
  const io::Frame f = seq.ReadFrame(5);
  EXPECT_EQ(f.color.width(), 64);
  EXPECT_GT(seq.ReadHdr(5)[100].y, 0.f);
  r = RunCli("info " + out);
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("hdr radiance  yes"), std::string::npos) << r.output;
  r = RunCli("contact-sheet " + out + " --out " + (dir / "sheet.png").string() + " --rows 3");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(cv::imread((dir / "sheet.png").string()).cols, 3 * 64 + 8);
}

TEST(Cli, SimulateSweepAndBadSettings) {
  test::TempDir dir;
  RunResult r = RunCli("simulate --out " + (dir / "sweep").string() +
                       " --sweep --sweep-exposures 1,4,16 --sweep-repeats 3 --size 32x24");
  ASSERT_EQ(r.status, 0) << r.output;
  const io::SequenceReader seq((dir / "sweep").string());
  ASSERT_EQ(seq.size(), 9u);
  EXPECT_DOUBLE_EQ(*seq.frames()[3].exposure_ms, 4.0);
  r = RunCli("simulate --out " + (dir / "x").string() + " --size 10by10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
  r = RunCli("simulate --out " + (dir / "x").string() + " --ae list --exposures 3,abc");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'abc'"), std::string::npos) << r.output;
  // An existing, non-empty output folder is refused and left alone.
  r = RunCli("simulate --out " + (dir / "sweep").string() + " --frames 2 --size 32x24");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("not empty"), std::string::npos) << r.output;
  EXPECT_EQ(io::SequenceReader((dir / "sweep").string()).size(), 9u);
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

TEST(Cli, CalibrateAndMergeASimulatedSweep) {
  test::TempDir dir;
  const std::string sweep = (dir / "sweep").string();
  RunResult r = RunCli("simulate --out " + sweep + " --sweep --sweep-repeats 3 --size 96x72");
  ASSERT_EQ(r.status, 0) << r.output;
  r = RunCli("calibrate " + sweep + " --out " + (dir / "s.json").string() + " --plots " +
             (dir / "plots").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("noise level function"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("median |deviation|"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("refined on the level thresholds"), std::string::npos) << r.output;
  const SensorInfo s = io::ReadSensorJson(dir / "s.json");
  ASSERT_TRUE(s.response && s.noise);
  EXPECT_FLOAT_EQ(s.response->table[1][128], 1.f);
  EXPECT_EQ(s.camera.width, 96);  // camera block carried over from the sweep
  for (const char* png : {"response.png", "derivative.png", "pcf.png"})
    EXPECT_TRUE(fs::exists(dir / "plots" / png)) << png;
  r = RunCli("merge " + sweep + " --sensor " + (dir / "s.json").string() + " --out " +
             (dir / "hdr.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(io::ReadExr(dir / "hdr.exr").width(), 96);
  // The classic method on request: another curve, said so.
  r = RunCli("calibrate " + sweep + " --out " + (dir / "c.json").string() + " --threshold-passes 0");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("debevec, classic"), std::string::npos) << r.output;
  const SensorInfo classic = io::ReadSensorJson(dir / "c.json");
  double differ = 0;
  for (int z = 10; z < 250; ++z) differ = std::max(differ, double(std::abs(classic.response->table[1][z] - s.response->table[1][z])));
  EXPECT_GT(differ, 1e-4);
  r = RunCli("calibrate " + sweep + " --out " + (dir / "e.json").string() + " --method emor");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--emor-basis"), std::string::npos) << r.output;
}

TEST(Cli, CalibrateRefusesASweepWithoutExposures) {
  test::TempDir dir;
  const std::string sweep = (dir / "sweep").string();
  ASSERT_EQ(RunCli("simulate --out " + sweep + " --sweep --sweep-repeats 1 --size 32x24").status, 0);
  fs::remove(dir / "sweep" / "exposure.txt");
  const RunResult r = RunCli("calibrate " + sweep + " --out " + (dir / "s.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("exposure.txt"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "s.json"));
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// The error-landscape figure: around the true pose of flickering frame pairs, the
// normalized-radiance and ICP error functions have their minimum at the truth and rise away
// from it.
TEST(Cli, ErrorLandscapeHasItsMinimumAtTheTruthForNormalizedRadianceAndIcp) {
  test::TempDir tmp;
  const std::string dir = (tmp / "landscape").string();
  const auto r = RunCli("bench --suite landscape --pairs 3 --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/landscape.json"));
  EXPECT_EQ(j["pairs_used"].get<int>(), 3);
  for (const char* f : {"normalized radiance (PCF)", "ICP (point-to-plane)"}) {
    const auto& s = j["summary"][f];
    EXPECT_EQ(s["min_at_truth_translation"].get<int>(), 3) << f;
    EXPECT_EQ(s["min_at_truth_rotation"].get<int>(), 3) << f;
    EXPECT_GT(s["contrast_translation"].get<double>(), 1.2) << f;
    EXPECT_GT(s["contrast_rotation"].get<double>(), 1.2) << f;
  }
  for (const auto& p : j["pairs"]) EXPECT_GE(std::abs(std::log2(p["exposure_ratio"].get<double>())), 1.0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/landscape_translation.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/landscape_rotation.png"));
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// The normalized-radiance figure: the pair with the largest exposure change, ten panels
// (two frames x colour, local mean, local std, NR, confidence), none of them blank.
TEST(Cli, NormalizedRadianceFigureShowsEveryMapForAStrongExposureChange) {
  test::TempDir tmp;
  const std::string dir = (tmp / "nr").string();
  const auto r = RunCli("bench --suite nr-figure --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/nr_figure.json"));
  EXPECT_GE(std::abs(std::log2(j["exposure_ratio"].get<double>())), 2.0);
  EXPECT_GT(j["pixels"].get<long>(), 1000);
  EXPECT_GT(j["radiance_mean_abs_log2_ratio"].get<double>(), 2.0);
  const cv::Mat sheet = cv::imread(dir + "/nr_figure.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(sheet.empty());
  ASSERT_EQ(sheet.cols % 5, 0);
  const int w = sheet.cols / 5, h = sheet.rows / 2;
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 5; ++col) {
      cv::Scalar mean, stddev;
      cv::meanStdDev(sheet(cv::Rect(col * w, row * h, w, h)), mean, stddev);
      EXPECT_GT(stddev[0], 10.0) << "panel " << col << " of frame " << row << " is blank";
    }
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

double Ate(const nlohmann::json& rows, const std::string& id) {
  for (const auto& r : rows)
    if (r["id"] == id) return r.contains("ate_rmse_m") ? r["ate_rmse_m"].get<double>() : -1;
  return -2;
}

// The tracking experiment on a short flicker sequence: every tracker gives a trajectory
// with per-frame errors; HDRFusion's default is accurate and raw intensity is not; the peers
// run on the same folder where hdrfusion-peers was built.
TEST(Cli, TrackingExperimentComparesEveryTrackerOnTheSameFrames) {
  test::TempDir tmp;
  const std::string out = (tmp / "results").string(), work = (tmp / "work").string();
  const auto r = RunCli("bench --suite tracking --frames 40 --ae flicker --out " + out + " --work " + work);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/tracking.json"));
  const auto& rows = j["flicker"]["trackers"];
  EXPECT_EQ(j["flicker"]["frames"].get<int>(), 40);
  for (const char* id : {"intensity", "ncc", "joint-exposure", "nr-f2f", "nr-f2m", "icp", "nr+icp"}) {
    EXPECT_GE(Ate(rows, id), 0) << id;
    for (const auto& row : rows)
      if (row["id"] == id) {
        EXPECT_EQ(row["trans_error_m"].size(), 40u) << id;
        EXPECT_GT(row["seconds"].get<double>(), 0) << id;
      }
  }
  EXPECT_LT(Ate(rows, "nr+icp"), 0.02);
  EXPECT_LT(Ate(rows, "nr-f2m"), 0.04);
  EXPECT_GT(Ate(rows, "intensity"), 2 * Ate(rows, "nr+icp"));
  EXPECT_TRUE(fs::exists(out + "/tracking_flicker_translation.png"));
  EXPECT_TRUE(fs::exists(out + "/tracking_flicker_rotation.png"));
  EXPECT_TRUE(fs::exists(work + "/room-flicker/rgb.txt"));
  const bool peers = fs::exists(fs::path(HDRF_CLI).parent_path() / "hdrfusion-peers");
  if (peers) {
    for (const char* id : {"opencv-rgbd", "opencv-icp", "opencv-rgbd-icp", "open3d"}) EXPECT_GE(Ate(rows, id), 0) << id;
    EXPECT_NE(Ate(rows, "opencv-kinfu"), -2);  // run, or reported unavailable with the reason
    EXPECT_TRUE(fs::exists(work + "/peers-flicker/open3d-tsdf.ply"));
    const auto bad = test::RunCommand((fs::path(HDRF_CLI).parent_path() / "hdrfusion-peers").string() + " " +
                                      (tmp / "missing").string() + " --out " + (tmp / "p").string());
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("missing"), std::string::npos) << bad.output;
    const auto bad_only = test::RunCommand((fs::path(HDRF_CLI).parent_path() / "hdrfusion-peers").string() + " " +
                                           work + "/room-flicker --only opencv --out " + (tmp / "p").string());
    EXPECT_EQ(bad_only.status, 1);
    EXPECT_NE(bad_only.output.find("unknown peer 'opencv'"), std::string::npos) << bad_only.output;
  } else {
    EXPECT_NE(r.output.find("peers not run"), std::string::npos) << r.output;
  }
}

// Radiance accuracy: the fused radiance of every scene is close to the truth, and the model's
// dynamic range is measured beside the scene's and the frames'.
TEST(Cli, RadianceSuiteMeasuresAccuracyAndDynamicRangePerScene) {
  test::TempDir tmp;
  const std::string out = (tmp / "results").string();
  const auto r = RunCli("bench --suite radiance --frames 15 --out " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/radiance.json"));
  ASSERT_EQ(j.size(), 4u);
  for (const auto& row : j) {
    const std::string what = row["scene"].get<std::string>() + "/" + row["ae"].get<std::string>();
    EXPECT_LT(row["radiance_median_stops"].get<double>(), 0.1) << what;
    EXPECT_GT(row["within_025_stop"].get<double>(), 0.7) << what;
    EXPECT_GT(row["model_range_stops"].get<double>(), 3.0) << what;
    EXPECT_GT(row["true_range_stops"].get<double>(), 3.0) << what;
    EXPECT_GT(row["frame_range_stops_max"].get<double>(), 1.0) << what;
  }
}

// bench --suite calibration on one sweep of three DoRF curves: every method within 1 % (band)
// of the true curves, the table and per-curve JSON written; a missing data folder is named.
TEST(Cli, CalibrationSuiteMeasuresEveryMethodOnDorfCurves) {
  const auto data = test::SharedDataDir();
  HDRF_SKIP_WITHOUT(test::SharedData("dorf/dorf_invI_201x1024.txt"), "dorf/dorf_invI_201x1024.txt");
  test::TempDir tmp;
  const std::string out = (tmp / "results").string();
  auto r = RunCli("bench --suite calibration --sweeps 1 --data " + data.string() + " --out " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/calibration.json"));
  for (const char* m : {"debevec", "robertson"}) {
    ASSERT_TRUE(j["methods"].contains(m)) << m;
    // 3 DoRF curves, the Xtion's 3 channels and, where present, BorealHDR's 3.
    EXPECT_GE(j["methods"][m]["curves"].size(), 6u);
    for (const auto& c : j["methods"][m]["curves"]) EXPECT_LT(c["band"].get<double>(), 0.01) << m << " " << c["curve"];
  }
  EXPECT_NE(test::ReadText(tmp / "results" / "calibration.md").find("| debevec | 3 |"), std::string::npos);
  // The noise level function: one row per curve and channel, each within 10 %.
  ASSERT_TRUE(j.contains("noise"));
  EXPECT_EQ(j["noise"].size(), j["methods"]["debevec"]["curves"].size());
  for (const auto& c : j["noise"]) {
    EXPECT_NEAR(c["sigma_s"].get<double>(), c["true_sigma_s"].get<double>(), 0.1 * c["true_sigma_s"].get<double>()) << c["curve"];
    EXPECT_NEAR(c["sigma_c"].get<double>(), c["true_sigma_c"].get<double>(), 0.1 * c["true_sigma_c"].get<double>()) << c["curve"];
  }
  EXPECT_NE(test::ReadText(tmp / "results" / "calibration.md").find("## Noise level function"), std::string::npos);
  r = RunCli("bench --suite calibration --sweeps 1 --data " + (tmp / "none").string() + " --out " + out);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("dorf_invI_201x1024.txt"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace hdrf
