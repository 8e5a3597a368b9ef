// Runs the real `hdrfusion-experiments` binary as the person regenerating docs/results would.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/test_support.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;

test::CommandResult RunExperiments(const std::string& args) {
  return test::RunCommand(std::string(HDRF_EXPERIMENTS) + " " + args);
}

// Every subcommand writes only where --out says: without it, it refuses to start.
TEST(Experiments, EverySubcommandNeedsItsOutputFolder) {
  for (const char* sub : {"landscape", "nr-figure", "tracking", "radiance", "paper"}) {
    const auto r = RunExperiments(sub);
    EXPECT_NE(r.status, 0) << sub;
    EXPECT_NE(r.output.find("--out"), std::string::npos) << sub << ": " << r.output;
  }
  test::TempDir tmp;
  const std::string out = (tmp / "results").string();
  const auto r = RunExperiments("calibration --out " + out);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--data"), std::string::npos) << r.output;
  const auto peers = RunExperiments("tracking --frames 5 --out " + out + " --peers /nonexistent/hdrfusion-peers");
  EXPECT_EQ(peers.status, 1);
  EXPECT_NE(peers.output.find("/nonexistent/hdrfusion-peers"), std::string::npos) << peers.output;
  EXPECT_FALSE(fs::exists(out)) << "nothing is written before the inputs are checked";
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// The error-landscape figure: around the true pose of flickering frame pairs, the
// normalized-radiance and ICP error functions have their minimum at the truth and rise away
// from it.
TEST(Experiments, ErrorLandscapeHasItsMinimumAtTheTruthForNormalizedRadianceAndIcp) {
  test::TempDir tmp;
  const std::string dir = (tmp / "landscape").string();
  const auto r = RunExperiments("landscape --pairs 3 --out " + dir);
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
TEST(Experiments, NormalizedRadianceFigureShowsEveryMapForAStrongExposureChange) {
  test::TempDir tmp;
  const std::string dir = (tmp / "nr").string();
  const auto r = RunExperiments("nr-figure --out " + dir);
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
TEST(Experiments, TrackingExperimentComparesEveryTrackerOnTheSameFrames) {
  test::TempDir tmp;
  const std::string out = (tmp / "results").string(), work = (tmp / "work").string();
  const auto r = RunExperiments("tracking --frames 40 --ae flicker --out " + out + " --work " + work +
                                (std::string(HDRF_PEERS).empty() ? "" : " --peers " + std::string(HDRF_PEERS)));
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
  const bool peers = !std::string(HDRF_PEERS).empty();
  if (peers) {
    for (const char* id : {"opencv-rgbd", "opencv-icp", "opencv-rgbd-icp", "open3d"}) EXPECT_GE(Ate(rows, id), 0) << id;
    EXPECT_NE(Ate(rows, "opencv-kinfu"), -2);  // run, or reported unavailable with the reason
    EXPECT_TRUE(fs::exists(work + "/peers-flicker/open3d-tsdf.ply"));
    const auto bad = test::RunCommand(std::string(HDRF_PEERS) + " " +
                                      (tmp / "missing").string() + " --out " + (tmp / "p").string());
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("missing"), std::string::npos) << bad.output;
    const auto bad_only = test::RunCommand(std::string(HDRF_PEERS) + " " +
                                           work + "/room-flicker --only opencv --out " + (tmp / "p").string());
    EXPECT_EQ(bad_only.status, 1);
    EXPECT_NE(bad_only.output.find("unknown peer 'opencv'"), std::string::npos) << bad_only.output;
  } else {
    EXPECT_NE(r.output.find("peers not run"), std::string::npos) << r.output;
  }
}

// Radiance accuracy: the fused radiance of every scene is close to the truth, and the model's
// dynamic range is measured beside the scene's and the frames'.
TEST(Experiments, RadianceSuiteMeasuresAccuracyAndDynamicRangePerScene) {
  test::TempDir tmp;
  const std::string out = (tmp / "results").string();
  const auto r = RunExperiments("radiance --frames 15 --out " + out);
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

// The calibration suite on one sweep of three DoRF curves: every method within 1 % (band)
// of the true curves, the table and per-curve JSON written; a missing data folder is named.
TEST(Experiments, CalibrationSuiteMeasuresEveryMethodOnDorfCurves) {
  const auto data = test::SharedDataDir();
  HDRF_SKIP_WITHOUT(test::SharedData("dorf/dorf_invI_201x1024.txt"), "dorf/dorf_invI_201x1024.txt");
  test::TempDir tmp;
  const std::string out = (tmp / "results").string();
  auto r = RunExperiments("calibration --sweeps 1 --data " + data.string() + " --out " + out);
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
  r = RunExperiments("calibration --sweeps 1 --data " + (tmp / "none").string() + " --out " + out);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("dorf_invI_201x1024.txt"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// A real recording (7-Scenes "redkitchen", ../shared/data: auto exposure, colour and depth
// not registered, no calibration), against the dataset's own poses: the photometric term
// does not make HDRFusion's tracking worse than depth alone, and where hdrfusion-peers is
// built, the default tracker is at least as accurate as Open3D's hybrid odometry on the same
// frames, in the same run.
TEST(Experiments, RealRecordingNrIcpIsAtLeastAsAccurateAsIcpAloneAndAsOpen3d) {
  const auto data = test::SharedData("7scenes_redkitchen");
  HDRF_SKIP_WITHOUT(data, "7scenes_redkitchen");
  test::TempDir tmp;
  const std::string out = (tmp / "results").string();
  const bool peers = !std::string(HDRF_PEERS).empty();
  const auto r = RunExperiments("real --data " + data.string() + " --out " + out +
                                (peers ? " --peers " + std::string(HDRF_PEERS) : ""));
  ASSERT_EQ(r.status, 0) << r.output;
  std::printf("%s", r.output.c_str());
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out + "/real.json"));
  const auto& rows = j["trackers"];
  EXPECT_EQ(j["frames"].get<int>(), 50);
  const double both = Ate(rows, "nr+icp"), icp = Ate(rows, "icp"), nr = Ate(rows, "nr-f2m");
  ASSERT_GE(both, 0);
  ASSERT_GE(icp, 0);
  ASSERT_GE(nr, 0);
  EXPECT_LE(both, icp);
  EXPECT_LT(both, 0.02);
  if (peers) {
    const double open3d = Ate(rows, "open3d");
    ASSERT_GE(open3d, 0);
    EXPECT_LE(both, open3d);
  } else {
    EXPECT_NE(r.output.find("peers not run"), std::string::npos) << r.output;
  }
  // A folder that is not a 7-Scenes recording is refused before anything is written.
  const auto bad = RunExperiments("real --data " + (tmp / "none").string() + " --out " + (tmp / "o2").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.output.find("frames/"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(tmp / "o2"));
}

}  // namespace
}  // namespace hdrf
