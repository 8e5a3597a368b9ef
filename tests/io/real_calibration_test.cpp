// Calibration on a real exposure sweep: Debevec & Malik's Memorial Church (16 scanned film
// exposures, 32 s to 1/1024 s, ../shared/data/memorial), compared with OpenCV's own
// CalibrateDebevec on the same images (an independent implementation).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/photo.hpp>

#include "io/sweep.h"
#include "radiometry/calibration.h"
#include "radiometry/validation.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

namespace fs = std::filesystem;
using namespace radiometry;

// The memorial images arranged as a sweep (docs/formats.md); returns the folder.
fs::path MakeMemorialSweep(const fs::path& src, const fs::path& dir,
                           std::vector<std::pair<std::string, double>>* list) {
  std::ifstream in(src / "exposures.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string name;
    double seconds;
    if (ss >> name >> seconds) list->emplace_back(name, seconds);
  }
  fs::create_directories(dir / "rgb");
  std::string rgb, exposure;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string t = std::to_string(1.0 + double(i));
    fs::create_symlink(src / (*list)[i].first, dir / "rgb" / (*list)[i].first);
    rgb += t + " rgb/" + (*list)[i].first + "\n";
    exposure += t + " " + std::to_string((*list)[i].second * 1000.0) + "\n";
  }
  test::WriteText(dir / "rgb.txt", rgb);
  test::WriteText(dir / "exposure.txt", exposure);
  test::WriteText(dir / "sensor.json",
                  R"({"camera": {"width": 512, "height": 768, "fx": 600, "fy": 600, "cx": 255.5,
                      "cy": 383.5}, "depth": {"scale": 1000}})");
  return dir;
}

TEST(RealCalibration, MemorialSweepAgainstOpenCvDebevec) {
  const auto src = test::SharedData("memorial");
  HDRF_SKIP_WITHOUT(src, "memorial");
  test::TempDir dir;
  std::vector<std::pair<std::string, double>> list;
  const Sweep sweep = ReadSweep(MakeMemorialSweep(src, dir.path(), &list));
  ASSERT_EQ(sweep.images.size(), 16u);
  // OpenCV implements the classic method: compare like with like (no threshold refinement).
  DebevecOptions classic;
  classic.threshold_passes = 0;
  const ResponseFit ours = FitDebevec(sweep, classic);

  std::vector<cv::Mat> images;
  std::vector<float> times;
  for (const auto& [name, seconds] : list) {
    images.push_back(cv::imread((src / name).string()));
    times.push_back(float(seconds));
  }
  cv::Mat cv_response;
  cv::createCalibrateDebevec()->process(images, cv_response, times);
  ASSERT_EQ(cv_response.rows, 256);
  for (int z : {5, 20, 50, 100, 128, 150, 200, 235, 250})
    std::printf("z %3d ours %.4f %.4f %.4f  opencv %.4f %.4f %.4f\n", z, ours.inverse.table[0][z],
                ours.inverse.table[1][z], ours.inverse.table[2][z], cv_response.at<cv::Vec3f>(z)[2],
                cv_response.at<cv::Vec3f>(z)[1], cv_response.at<cv::Vec3f>(z)[0]);
  // Compare shapes after one scale per channel, in log terms, over well-sampled levels.
  double worst = 0, sum = 0;
  int n = 0, worst_z = 0, worst_c = 0;
  for (int c = 0; c < 3; ++c) {
    const int cv_c = 2 - c;  // OpenCV is BGR
    double mean_log_ratio = 0;
    for (int z = 20; z <= 235; ++z)
      mean_log_ratio += std::log(cv_response.at<cv::Vec3f>(z)[cv_c] / ours.inverse.table[c][z]);
    mean_log_ratio /= 216.0;
    for (int z = 20; z <= 235; ++z) {
      const double d = std::abs(std::log(cv_response.at<cv::Vec3f>(z)[cv_c] / ours.inverse.table[c][z]) -
                                mean_log_ratio);
      if (d > worst) worst = d, worst_z = z, worst_c = c;
      sum += d;
      ++n;
    }
  }
  std::printf("memorial: ours vs OpenCV CalibrateDebevec, levels 20-235: mean |log ratio| %.4f, "
              "worst %.4f at level %d of channel %d (after one scale per channel); our rms log residual "
              "%.3f %.3f %.3f\n", sum / n, worst, worst_z, worst_c, ours.rms_log_residual[0], ours.rms_log_residual[1],
              ours.rms_log_residual[2]);
  // Measured 2026-11-22: mean 0.085, worst 0.82 (OpenCV samples 70 pixels and its curve is not
  // monotonic on this sweep). Asserted with a little room so that a regression fails.
  EXPECT_LT(sum / n, 0.12);
  EXPECT_LT(worst, 1.0);

  // The merged radiance is consistent across exposures, with the curve `calibrate` writes
  // (refined on the level thresholds) and with the classic one.
  NoiseModel noise;
  noise.sigma_s = {0.02f, 0.02f, 0.02f};
  noise.sigma_c = {0.002f, 0.002f, 0.002f};
  auto consistency = [&](const ResponseFit& fit) {
    const RadianceImage merged = MergeHdr(sweep, fit.inverse, noise);
    std::vector<double> med;
    for (const auto& e : MergeConsistency(sweep, fit.inverse, merged)) {
      std::printf("  %9.4g ms: median |deviation| %.3f stops (%ld samples)\n", e.exposure_ms,
                  e.median_abs_stops, e.samples);
      if (e.samples > 10000) med.push_back(e.median_abs_stops);
    }
    EXPECT_GT(med.size(), 8u);
    std::sort(med.begin(), med.end());
    return med.empty() ? 1e9 : med[med.size() / 2];
  };
  const double refined = consistency(FitDebevec(sweep)), plain = consistency(ours);
  std::printf("memorial: merged radiance consistency (median over exposures) %.3f stops refined, %.3f "
              "classic\n", refined, plain);
  // Measured: 0.120 refined, 0.147 classic (film with a strong toe near level 17 makes dark
  // samples scatter); the synthetic equivalent is 0.02 (tests/radiometry).
  EXPECT_LT(refined, 0.2);
  EXPECT_LT(plain, 0.2);
  EXPECT_LT(refined, plain);
}

// The check `calibrate` makes before writing, on a real sweep: the film's nominal shutter
// times put the short exposures a few tenths of a stop off, which is marginal (written, with
// the reasons), not a calibration to refuse; the scene covers almost every level.
TEST(RealCalibration, MemorialSweepIsJudgedMarginalNotRefused) {
  const auto src = test::SharedData("memorial");
  HDRF_SKIP_WITHOUT(src, "memorial");
  test::TempDir dir;
  std::vector<std::pair<std::string, double>> list;
  const Sweep sweep = ReadSweep(MakeMemorialSweep(src, dir.path(), &list));
  ASSERT_NO_THROW(CheckSweepForCalibration(sweep));
  const ResponseFit fit = FitDebevec(sweep);
  NoiseModel noise;
  noise.sigma_s = {0.02f, 0.02f, 0.02f};
  noise.sigma_c = {0.002f, 0.002f, 0.002f};
  const CalibrationCheck check =
      CheckCalibration(sweep, fit.inverse, noise, std::nullopt, [](const Sweep& s) { return FitDebevec(s).inverse; });
  std::printf("memorial: verdict %s, held back %.4g ms predicted within %.3f stops, coverage %.2f %.2f %.2f\n",
              VerdictName(check.verdict), check.held_out.exposure_ms, check.held_out.median_abs_stops,
              check.coverage.share[0], check.coverage.share[1], check.coverage.share[2]);
  for (const auto& r : check.reasons) std::printf("  - %s\n", r.c_str());
  EXPECT_EQ(check.verdict, Verdict::kMarginal);
  EXPECT_GT(check.held_out.median_abs_stops, 0.1);  // measured 0.19
  EXPECT_LT(check.held_out.median_abs_stops, 0.3);
  for (int c = 0; c < 3; ++c) EXPECT_GT(check.coverage.share[c], 0.95) << c;
}

}  // namespace
}  // namespace hdrf::io
