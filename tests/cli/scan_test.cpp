// The engine end to end, as a user runs it: `hdrfusion simulate` a 300-frame 320x240 flicker
// sequence of the built-in room (seed 1), `scan` it with each tracker, `eval` the result.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include "io/image_io.h"
#include "io/ply.h"
#include "support/test_support.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult RunCli(const std::string& args) { return test::RunCommand(std::string(HDRF_CLI) + " " + args); }

nlohmann::json ReadJson(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

class ScanAccuracy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    const RunResult r = RunCli("simulate --out " + Seq() + " --scene room --seed 1 --frames 300 --size 320x240 --ae flicker");
    ASSERT_EQ(r.status, 0) << r.output;
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string Seq() { return (dir_->path() / "flicker").string(); }
  static nlohmann::json ScanAndEval(const std::string& tracker, nlohmann::json* report) {
    const std::string out = (dir_->path() / ("scan_" + tracker)).string();
    RunResult r = RunCli("scan " + Seq() + " --out " + out + " --tracker " + tracker);
    EXPECT_EQ(r.status, 0) << r.output;
    r = RunCli("eval " + Seq() + " " + out);
    EXPECT_EQ(r.status, 0) << r.output;
    std::printf("[%s]\n%s", tracker.c_str(), r.output.c_str());
    *report = ReadJson(fs::path(out) / "report.json");
    return ReadJson(fs::path(out) / "eval.json");
  }
  static test::TempDir* dir_;
};
test::TempDir* ScanAccuracy::dir_ = nullptr;

TEST_F(ScanAccuracy, NormalizedRadianceAndIcpBeatBrightnessConstancy) {
  nlohmann::json rep_nr, rep_nricp, rep_int;
  const auto nr = ScanAndEval("nr", &rep_nr);
  const auto nricp = ScanAndEval("nr+icp", &rep_nricp);
  const auto in = ScanAndEval("intensity", &rep_int);
  // Trajectory (targets of the engine issue).
  EXPECT_LE(nr["ate_rmse_m"].get<double>(), 0.02);
  EXPECT_LE(nricp["ate_rmse_m"].get<double>(), 0.01);
  // The brightness-constancy baseline is at least 5x worse, or loses track.
  const bool baseline_lost = rep_int["lost_frames"].get<int>() > 30;
  EXPECT_TRUE(baseline_lost || in["ate_rmse_m"].get<double>() >= 5 * nr["ate_rmse_m"].get<double>())
      << "intensity ATE " << in["ate_rmse_m"] << ", lost " << rep_int["lost_frames"];
  // Exposure ratios against the true ones.
  std::printf("lost frames: nr %d, nr+icp %d, intensity %d; exposure ratio median relative error (nr+icp) %.2f %%\n",
              rep_nr["lost_frames"].get<int>(), rep_nricp["lost_frames"].get<int>(), rep_int["lost_frames"].get<int>(),
              100 * rep_nricp["exposure_median_relative_error"].get<double>());
  EXPECT_LE(rep_nricp["exposure_median_relative_error"].get<double>(), 0.02);
  // Fused radiance and geometry against the scene.
  EXPECT_LE(nricp["radiance_median_error_stops"].get<double>(), 0.1);
  const double voxel = rep_nricp["options"]["volume"]["voxel_m"].get<double>();
  EXPECT_LE(nricp["mesh_median_distance_m"].get<double>(), 0.5 * voxel);
  // Outputs as docs/formats.md says.
  const fs::path out = dir_->path() / "scan_nr+icp";
  for (const char* f : {"trajectory.txt", "mesh.ply", "render_last.exr", "render_last.png", "render_first.png", "report.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const std::string ply = test::ReadText(out / "mesh.ply").substr(0, 600);
  EXPECT_NE(ply.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(ply.find("property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                     "property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                     "property float radiance_r\nproperty float radiance_g\nproperty float radiance_b\n"
                     "element face"), std::string::npos) << ply;
  EXPECT_NE(ply.find("property list uchar int vertex_indices"), std::string::npos);
  EXPECT_GT(io::ReadPly(out / "mesh.ply").triangles.size(), 10000u);
  EXPECT_EQ(rep_nricp["frames_detail"].size(), 300u);
}

TEST(ScanErrors, MissingCalibrationBadSettingsAndOptionFiles) {
  test::TempDir dir;
  const std::string seq = (dir / "seq").string();
  ASSERT_EQ(RunCli("simulate --out " + seq + " --frames 6 --size 64x48").status, 0);
  // Strip the calibration: refused, with the documented fallback named.
  test::WriteText(dir / "seq" / "sensor.json",
                  R"({"camera": {"width": 64, "height": 48, "fx": 53.9, "fy": 53.9, "cx": 31.5,
                      "cy": 23.5}, "depth": {"scale": 5000}})");
  RunResult r = RunCli("scan " + seq + " --out " + (dir / "o1").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("sensor.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--response srgb"), std::string::npos) << r.output;
  r = RunCli("scan " + seq + " --out " + (dir / "o2").string() + " --response srgb --voxel-size 0.125");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("the sRGB curve is assumed"), std::string::npos) << r.output;  // said, not silent
  EXPECT_TRUE(fs::exists(dir / "o2" / "mesh.ply"));
  // Impossible settings.
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --voxel-size 0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'volume.voxel_m': 0 is out of range"), std::string::npos) << r.output;
  // The fixed cube's flags are refused saying what replaced them.
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --volume-res 100");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'--volume-res': was removed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("volume.voxel_m"), std::string::npos) << r.output;
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --volume.size_m 8");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'--volume.size_m': was removed"), std::string::npos) << r.output;
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --tracker.kind orb");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'tracker.kind': 'orb' is not one of nr+icp, nr, icp, intensity"), std::string::npos)
      << r.output;
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --nr.patch seven");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'nr.patch': 'seven' is not a number"), std::string::npos) << r.output;
  r = RunCli("scan synthetic:scene=castle --out " + (dir / "o3").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("castle"), std::string::npos) << r.output;
  test::WriteText(dir / "opts.json", R"({"volume": {"voxel_mm": 10}})");
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --options " + (dir / "opts.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("opts.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("volume.voxel_mm"), std::string::npos) << r.output;
  // Wrong types in a settings file are refused naming the file and the key.
  test::WriteText(dir / "opts.json", R"({"volume": {"voxel_m": "big"}})");
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --options " + (dir / "opts.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("opts.json: 'volume.voxel_m' must be a number"), std::string::npos) << r.output;
  test::WriteText(dir / "opts.json", R"({"volume": 5})");
  r = RunCli("scan synthetic:frames=2 --out " + (dir / "o3").string() + " --options " + (dir / "opts.json").string());
  EXPECT_NE(r.output.find("'volume' is a section"), std::string::npos) << r.output;
  // A frame that goes missing midway: the error is reported, no output is written, and the
  // model so far is kept in the recovery file (tests/cli/project_cli_test.cpp follows it up).
  fs::remove(dir / "seq" / "rgb" / (std::string("1.133333") + ".png"));
  r = test::RunCommand("XDG_STATE_HOME=" + (dir / "state").string() + " " + HDRF_CLI + " scan " + seq + " --out " +
                       (dir / "o4").string() + " --response srgb --voxel-size 0.125");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("1.133333.png"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("frames scanned are kept in " + (dir / "state").string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "o4" / "mesh.ply"));
  EXPECT_FALSE(fs::exists(dir / "o4" / "trajectory.txt"));
}

// Blank first depth frames: the scan starts at the first frame with depth; a sequence with
// no depth at all fails, saying why, and writes nothing.
TEST(ScanErrors, TheFirstFrameWithDepthAnchorsTheModel) {
  test::TempDir dir;
  const std::string seq = (dir / "seq").string();
  ASSERT_EQ(RunCli("simulate --out " + seq + " --frames 12 --size 80x60").status, 0);
  std::vector<fs::path> depth;
  for (const auto& e : fs::directory_iterator(dir / "seq" / "depth")) depth.push_back(e.path());
  std::sort(depth.begin(), depth.end());
  ASSERT_EQ(depth.size(), 12u);
  const DepthRawImage zero(80, 60);
  for (int i = 0; i < 3; ++i) io::WriteDepthPng(depth[std::size_t(i)], zero);
  RunResult r = RunCli("scan " + seq + " --out " + (dir / "o1").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("frame 0: waiting (waiting for a frame to anchor the model: 0 % of its pixels have depth"),
            std::string::npos) << r.output;
  const nlohmann::json rep = ReadJson(dir / "o1" / "report.json");
  EXPECT_EQ(rep["waiting_frames"].get<int>(), 3);
  EXPECT_EQ(rep["fused_frames"].get<int>(), 9);
  EXPECT_EQ(rep["frames_detail"][0]["state"], "waiting");
  EXPECT_EQ(rep["frames_detail"][3]["state"], "tracked");
  EXPECT_GT(rep["mesh"]["vertices"].get<int>(), 1000);
  for (const auto& f : depth) io::WriteDepthPng(f, zero);
  r = RunCli("scan " + seq + " --out " + (dir / "o2").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("none of the 12 frames could anchor the model"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("tracker.min_anchor_depth"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "o2" / "report.json"));
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// A 7-Scenes recording's frames (frame-NNNNNN.color.png or .jpg, .depth.png, .pose.txt) as a
// sequence in the TUM layout, by links, as a user converting them would.
void SevenScenesAsSequence(const fs::path& src, const fs::path& seq) {
  fs::create_directories(seq / "rgb");
  fs::create_directories(seq / "depth");
  std::vector<std::string> stems;
  for (const auto& e : fs::directory_iterator(src)) {
    const std::string name = e.path().filename().string();
    if (name.size() > 10 && name.rfind(".pose.txt") == name.size() - 9) stems.push_back(name.substr(0, name.size() - 9));
  }
  std::sort(stems.begin(), stems.end());
  std::string rgb, depth, gt;
  for (const std::string& n : stems) {
    const int k = std::stoi(n.substr(6));
    char t[32];
    std::snprintf(t, sizeof t, "%.6f", k / 30.0);
    const std::string ext = fs::exists(src / (n + ".color.png")) ? ".png" : ".jpg";
    fs::create_symlink(src / (n + ".color" + ext), seq / "rgb" / (n + ext));
    fs::create_symlink(src / (n + ".depth.png"), seq / "depth" / (n + ".png"));
    rgb += std::string(t) + " rgb/" + n + ext + "\n";
    depth += std::string(t) + " depth/" + n + ".png\n";
    // 4x4 camera-to-world matrix -> TUM line.
    std::ifstream in(src / (n + ".pose.txt"));
    Eigen::Matrix4d M;
    for (int i = 0; i < 16; ++i) in >> M(i / 4, i % 4);
    const Eigen::Quaterniond q(Eigen::Matrix3d(M.block<3, 3>(0, 0)));
    char line[256];
    std::snprintf(line, sizeof line, "%s %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", t, M(0, 3), M(1, 3), M(2, 3),
                  q.x(), q.y(), q.z(), q.w());
    gt += line;
  }
  test::WriteText(seq / "rgb.txt", rgb);
  test::WriteText(seq / "depth.txt", depth);
  test::WriteText(seq / "groundtruth.txt", gt);
  test::WriteText(seq / "sensor.json", R"({"camera": {"width": 640, "height": 480, "fx": 585, "fy": 585,
                                          "cx": 320, "cy": 240}, "depth": {"scale": 1000}})");
}

// A real recording: 50 Kinect v1 frames of 7-Scenes "redkitchen" (../shared/data), with
// KinectFusion poses as reference; no calibration, so --response srgb.
TEST(ScanReal, SevenScenesKitchenAgainstItsReferencePoses) {
  const auto src = test::SharedData("7scenes_redkitchen/frames");
  HDRF_SKIP_WITHOUT(src, "7scenes_redkitchen");
  test::TempDir dir;
  const fs::path seq = dir / "kitchen";
  SevenScenesAsSequence(src, seq);
  const std::string out = (dir / "scan").string();
  RunResult r = RunCli("scan " + seq.string() + " --out " + out + " --response srgb");
  ASSERT_EQ(r.status, 0) << r.output;
  r = RunCli("eval " + seq.string() + " " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  std::printf("%s", r.output.c_str());
  const auto ev = ReadJson(fs::path(out) / "eval.json");
  const auto rep = ReadJson(fs::path(out) / "report.json");
  EXPECT_EQ(rep["lost_frames"].get<int>(), 0);
  // Measured 2026-11-24: 0.86 cm (1.99 cm before the tracker measured its terms' scales)
  // against poses that are themselves KinectFusion estimates.
  EXPECT_LT(ev["ate_rmse_m"].get<double>(), 0.015);
}

// 500 real frames (7-Scenes "redkitchen" 500-999: 3.4 m walked, 885 degrees turned; colour and
// depth not registered, auto exposure, no calibration), long enough for drift to show. With
// the depth's noise model a real Kinect needs (tracker.depth_noise_scaling) and the colour
// weighed by its fit (tracker.photo_agreement: this colour is not registered) the tracker holds
// within 2 cm of the reference (measured 1.86 cm with icp, 1.88 with nr+icp; a KinectFusion-
// class tracker, InfiniTAM v3's depth-only ICP at 2 cm voxels, holds 1.78 cm), and the
// photometric term, which does not fit this colour, does not make it worse than depth alone:
// each frame's report says which terms tracked it and with what weight.
TEST(ScanReal, SevenScenesKitchen500FramesHoldTwoCentimetres) {
  const auto src = test::SharedData("7scenes_redkitchen_500_999/frames");
  HDRF_SKIP_WITHOUT(src, "7scenes_redkitchen_500_999");
  test::TempDir dir;
  const fs::path seq = dir / "kitchen";
  SevenScenesAsSequence(src, seq);
  double ate[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::string out = (dir / (k == 0 ? "default" : "icp")).string();
    RunResult r = RunCli("scan " + seq.string() + " --out " + out + " --response srgb --tracker.depth_noise_scaling true --tracker.photo_agreement true" +
                         (k == 1 ? " --tracker icp" : ""));
    ASSERT_EQ(r.status, 0) << r.output;
    r = RunCli("eval " + seq.string() + " " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    std::printf("%s: %s", k == 0 ? "nr+icp" : "icp", r.output.c_str());
    ate[k] = ReadJson(fs::path(out) / "eval.json")["ate_rmse_m"].get<double>();
    const auto rep = ReadJson(fs::path(out) / "report.json");
    EXPECT_EQ(rep["fused_frames"].get<int>(), 500);
    int photo_used = 0;
    double depth_ref = 0;
    for (const auto& f : rep["frames_detail"]) {
      if (f["index"].get<int>() == 0) continue;  // the anchor: no tracking
      const auto& terms = f["tracking"]["terms"];
      EXPECT_EQ(terms["icp"].get<double>(), 1.0) << f["index"];
      const double photo = terms["photometric"].get<double>();
      EXPECT_GE(photo, 0.0);
      EXPECT_LE(photo, k == 0 ? 1.0 : 0.0);
      photo_used += photo > 0;
      depth_ref = std::max(depth_ref, f["tracking"]["icp_depth_ref_m"].get<double>());
    }
    // The residual scale is set at the frames' median depth (0.8-3.4 m here).
    EXPECT_GT(depth_ref, 0.8);
    EXPECT_LT(depth_ref, 4.0);
    std::printf("  frames with a photometric share: %d of 499\n", photo_used);
  }
  EXPECT_LE(ate[0], 0.02);
  EXPECT_LE(ate[1], 0.02);
  // Not worse than depth alone (within 1 mm: the photometric term's small share moves poses).
  EXPECT_LE(ate[0], ate[1] + 0.001);
}

}  // namespace
}  // namespace hdrf
