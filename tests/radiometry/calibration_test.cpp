// Calibration against known truth: simulated sweeps through real measured response curves
// (the built-in Xtion profile always; DoRF, EMoR and BorealHDR curves from ../shared/data
// where present), then the real Memorial sweep (tests/io).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>
#include <cmath>

#include "common/error.h"
#include "eval/response_error.h"
#include "response_curves.h"
#include "sim/sweep_simulator.h"
#include "radiometry/calibration.h"
#include "radiometry/pcf.h"
#include "sim/builtin_sensor.h"
#include "sim/synthetic_source.h"
#include "support/test_support.h"

namespace hdrf::radiometry {
namespace {

using sim::SimulateSweep;

const NoiseModel& kTestNoise = sim::kSweepNoise;

InverseResponse Normalised(InverseResponse r) {
  ScaleToUnitAt128(r);
  return r;
}

InverseResponse DorfTriplet(const std::vector<std::vector<double>>& rows, int k_r, int k_g, int k_b) {
  return experiments::InverseFromCurves({&rows.at(std::size_t(k_r)), &rows.at(std::size_t(k_g)), &rows.at(std::size_t(k_b))});
}

// The target is 1 % of full range over levels 5..250 (CompareResponse, after one scale per
// channel), asserted per channel for every method on the `band` figure (the estimate maps
// back to the right level through the true camera), and on the pointwise figure wherever
// the true camera's level bands are all narrower than 2 % of the range. Where a measured
// curve jumps (DoRF 130: the forward response is flat across bands of up to 9 % of its range
// at levels 249-253) no image can place f^-1 inside the band; the pointwise figure is held
// at 4 % there. Robertson missed on the strongly compressive DoRF 171 (1.1 %) until the
// threshold refinement (RobertsonOptions::threshold_passes); the classic method is checked
// separately below.
void CheckMethods(const InverseResponse& truth, const char* name, bool with_emor) {
  const Sweep s = SimulateSweep(truth, kTestNoise);
  std::vector<ResponseFit> fits = {FitDebevec(s), FitRobertson(s)};
  if (with_emor) {
    const auto basis_file = test::SharedData("emor/invemor.txt");
    if (!basis_file.empty()) fits.push_back(FitEmor(s, EmorBasis::Load(basis_file)));
  }
  std::printf("%s, worst error over levels 5-250 as a share of full range (pointwise / from "
              "the level's band):", name);
  for (const ResponseFit& fit : fits) {
    const eval::ResponseAccuracy a = eval::CompareResponse(fit.inverse, truth);
    std::printf(" %s %.4f / %.4f", fit.method.c_str(), a.PointMax(), a.BinMax());
    if (fit.method == "emor")  // the warning of `calibrate` stays quiet where EMoR fits
      EXPECT_LT(std::max({fit.basis_gap[0], fit.basis_gap[1], fit.basis_gap[2]}), 0.01) << name;
    for (int c = 0; c < 3; ++c) {
      const double target = 0.01;
      EXPECT_LT(a.bin[c], target) << name << " " << fit.method << " " << c;
      EXPECT_LT(a.point[c], a.widest_bin[c] < 0.02 ? target : 0.04) << name << " " << fit.method << " " << c;
      EXPECT_FLOAT_EQ(fit.inverse.table[c][128], 1.0f);  // the documented scale
      for (int i = 1; i < 256; ++i) ASSERT_GE(fit.inverse.table[c][i], fit.inverse.table[c][i - 1]);
    }
  }
  std::printf("\n");
}

TEST(Calibration, RecoversTheXtionResponse) {
  CheckMethods(Normalised(*sim::BuiltinXtionProfile().response), "xtion", true);
}

// Triplets across the database, with its hardest curves for each method in the last one
// (hdrfusion-experiments calibration runs all 201).
TEST(Calibration, RecoversDorfResponses) {
  const auto file = test::SharedData("dorf/dorf_invI_201x1024.txt");
  HDRF_SKIP_WITHOUT(file, "dorf/dorf_invI_201x1024.txt");
  const auto rows = experiments::LoadDorfInverseCurves(file);
  ASSERT_EQ(rows.size(), 201u);
  for (std::array<int, 3> k : {std::array{0, 3, 7}, std::array{57, 60, 64}, std::array{123, 126, 130},
                               std::array{190, 193, 197}, std::array{165, 171, 159}}) {
    const std::string name = "dorf " + std::to_string(k[0]) + "/" + std::to_string(k[1]) + "/" + std::to_string(k[2]);
    CheckMethods(DorfTriplet(rows, k[0], k[1], k[2]), name.c_str(), true);
  }
}

// The threshold refinement against the classic methods on the curves where the classic
// Robertson missed most (desk scene: DoRF 168-171 at 1.2-1.5 % of the range): the level
// averages lean towards the scene's dense radiances, the probit thresholds do not.
TEST(Calibration, ThresholdRefinementRemovesTheSceneHistogramPull) {
  const auto file = test::SharedData("dorf/dorf_invI_201x1024.txt");
  HDRF_SKIP_WITHOUT(file, "dorf/dorf_invI_201x1024.txt");
  const auto rows = experiments::LoadDorfInverseCurves(file);
  const InverseResponse truth = DorfTriplet(rows, 169, 170, 171);
  const Sweep s = SimulateSweep(truth, kTestNoise, 2, 160, 120, "desk");
  RobertsonOptions classic_r, refined_r;
  classic_r.threshold_passes = 0;
  DebevecOptions classic_d, refined_d;
  classic_d.threshold_passes = 0;
  const double r0 = eval::CompareResponse(FitRobertson(s, classic_r).inverse, truth).BinMax();
  const double r2 = eval::CompareResponse(FitRobertson(s, refined_r).inverse, truth).BinMax();
  const double d0 = eval::CompareResponse(FitDebevec(s, classic_d).inverse, truth).BinMax();
  const double d2 = eval::CompareResponse(FitDebevec(s, refined_d).inverse, truth).BinMax();
  std::printf("dorf 169/170/171 desk, worst band error: robertson %.4f -> %.4f, debevec %.4f -> %.4f\n",
              r0, r2, d0, d2);
  EXPECT_GT(r0, 0.01);  // the classic Robertson's known miss
  EXPECT_LT(r2, 0.01);
  EXPECT_LT(r2, 0.6 * r0);
  EXPECT_LT(d2, 0.01);
  EXPECT_LE(d2, d0);
}

TEST(Calibration, RecoversBorealHdrMeasuredResponse) {
  const auto file = test::SharedData("camera_response_measured/borealhdr_pcalib_inside1.txt");
  HDRF_SKIP_WITHOUT(file, "camera_response_measured/borealhdr_pcalib_inside1.txt");
  const InverseResponse truth = experiments::LoadPcalibResponse(file);
  CheckMethods(truth, "borealhdr", false);
  // A machine-vision response outside the EMoR basis: the fit misses 1 % and the
  // basis-gap warning of `calibrate` says so.
  const auto basis_file = test::SharedData("emor/invemor.txt");
  if (basis_file.empty()) return;
  const ResponseFit em = FitEmor(SimulateSweep(truth, kTestNoise), EmorBasis::Load(basis_file));
  const eval::ResponseAccuracy a = eval::CompareResponse(em.inverse, truth);
  const double gap = std::max({em.basis_gap[0], em.basis_gap[1], em.basis_gap[2]});
  std::printf("borealhdr emor: point %.4f band %.4f, basis gap %.4f\n", a.PointMax(), a.BinMax(), gap);
  EXPECT_GT(a.BinMax(), 0.01);
  EXPECT_GT(gap, 0.01);
}

// The two figures on hand-made cases: an estimate inside the true level's band scores 0 on
// `bin` and its offset on `point`; one outside scores its distance to the band.
TEST(Calibration, ResponseAccuracyFigures) {
  InverseResponse truth;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) truth.table[c][i] = float(i);  // bands of width 1 (of 255)
  InverseResponse inside = truth, outside = truth;
  inside.table[1][100] += 0.4f;
  outside.table[2][200] += 2.0f;  // 1.5 beyond the band's upper edge
  const eval::ResponseAccuracy a = eval::CompareResponse(inside, truth);
  EXPECT_NEAR(a.point[1], 0.4 / 255, 1e-4);
  EXPECT_EQ(a.point_level[1], 100);
  EXPECT_NEAR(a.BinMax(), 0.0, 1e-4);
  const eval::ResponseAccuracy b = eval::CompareResponse(outside, truth);
  EXPECT_NEAR(b.bin[2], 1.5 / 255, 1e-4);
  EXPECT_EQ(b.bin_level[2], 200);
  EXPECT_NEAR(b.widest_bin[0], 1.0 / 255, 1e-6);
  // A scaled estimate is as good as the truth (one scale per channel is free).
  InverseResponse scaled = truth;
  for (float& v : scaled.table[0]) v *= 3;
  EXPECT_LT(eval::CompareResponse(scaled, truth).PointMax(), 1e-6);
}

TEST(Calibration, DorfFileErrorsNamed) {
  test::TempDir dir;
  test::WriteText(dir / "short.txt", "# comment\n0 0.5 1\n");
  test::ExpectErrorContaining([&] { experiments::LoadDorfInverseCurves(dir / "short.txt"); },
                              {"short.txt:2", "3 values, expected 1024"});
  std::string bad;
  for (int j = 0; j < 1024; ++j) bad += j == 7 ? "x " : "0.5 ";
  test::WriteText(dir / "bad.txt", bad + "\n");
  test::ExpectErrorContaining([&] { experiments::LoadDorfInverseCurves(dir / "bad.txt"); }, {"bad.txt", "'x'"});
  test::ExpectErrorContaining([&] { experiments::LoadDorfInverseCurves(dir / "none.txt"); }, {"none.txt", "missing"});
  test::WriteText(dir / "pcalib.txt", "0 1 2\n");
  test::ExpectErrorContaining([&] { experiments::LoadPcalibResponse(dir / "pcalib.txt"); },
                              {"pcalib.txt", "3 values, expected 256"});
}

// sigma_s and sigma_c within 10 % with the response fitted from the same sweep (6 frames per
// exposure), as `calibrate` does it. `truth` is in the calibration's units (f^-1(128) = 1),
// so the sigmas compare directly.
void CheckNoise(const InverseResponse& truth, const NoiseModel& noise, const char* name,
                const std::string& scene = "room") {
  const Sweep s = SimulateSweep(truth, noise, 6, 160, 120, scene);
  const NoiseFit nf = FitNoise(s, FitDebevec(s).inverse);
  for (int c = 0; c < 3; ++c) {
    const double ss = nf.noise.sigma_s[c], sc = nf.noise.sigma_c[c];
    std::printf("%s channel %d: sigma_s %.4f (true %.4f), sigma_c %.4f (true %.4f), %zu thresholds, "
                "fit residual %.3f\n", name, c, ss, noise.sigma_s[c], sc, noise.sigma_c[c],
                nf.levels[c].size(), nf.rms_relative_residual[c]);
    EXPECT_NEAR(ss, noise.sigma_s[c], 0.1 * noise.sigma_s[c]) << name << " " << c;
    EXPECT_NEAR(sc, noise.sigma_c[c], 0.1 * noise.sigma_c[c]) << name << " " << c;
    // The thresholds ascend with the level and lie where the true camera switches levels.
    const auto& th = nf.levels[c];
    ASSERT_GE(th.size(), 100u) << name << " " << c;
    for (std::size_t i = 1; i < th.size(); ++i) ASSERT_GT(th[i].level, th[i - 1].level);
  }
}

TEST(Calibration, NoiseLevelFunctionWithinTenPercent) {
  CheckNoise(Normalised(*sim::BuiltinXtionProfile().response), kTestNoise, "xtion");
  // A quieter and a noisier sensor, on the other scene.
  NoiseModel quiet = kTestNoise, loud = kTestNoise;
  for (int c = 0; c < 3; ++c) {
    quiet.sigma_s[c] *= 0.5f, quiet.sigma_c[c] *= 0.4f;
    loud.sigma_s[c] *= 2.0f, loud.sigma_c[c] *= 1.5f;
  }
  CheckNoise(Normalised(*sim::BuiltinXtionProfile().response), quiet, "xtion quiet", "desk");
  CheckNoise(Normalised(*sim::BuiltinXtionProfile().response), loud, "xtion loud", "desk");
}

// The curves whose dark levels defeated the earlier per-level estimate (variance of f^-1(I)
// over repeats, which leans on the fitted response's slope in the dark levels: sigma_c was
// off by 41-71 % on DoRF 144-159, and by more than 10 % on 61 of the 201 curves).
TEST(Calibration, NoiseLevelFunctionOnDorfCurves) {
  const auto file = test::SharedData("dorf/dorf_invI_201x1024.txt");
  HDRF_SKIP_WITHOUT(file, "dorf/dorf_invI_201x1024.txt");
  const auto rows = experiments::LoadDorfInverseCurves(file);
  CheckNoise(DorfTriplet(rows, 12, 146, 159), kTestNoise, "dorf 12/146/159");
  CheckNoise(DorfTriplet(rows, 165, 171, 193), kTestNoise, "dorf 165/171/193");
}

// Threshold radiances: where the fit puts the sensor's switch from one level to the next,
// against the true camera (midway between its table values), with the true response.
TEST(Calibration, NoiseThresholdsLieWhereTheCameraSwitchesLevels) {
  const InverseResponse truth = Normalised(*sim::BuiltinXtionProfile().response);
  const Sweep s = SimulateSweep(truth, kTestNoise, 6);
  const NoiseFit nf = FitNoise(s, truth);
  for (int c = 0; c < 3; ++c) {
    int checked = 0;
    double worst = 0;
    for (const NoiseLevel& l : nf.levels[c]) {
      const int k = int(l.level + 0.5);
      if (k < 16 || k > 240) continue;
      const double tau = 0.5 * (truth.table[c][k - 1] + truth.table[c][k]);
      const double sigma = std::sqrt(l.variance);
      worst = std::max(worst, std::abs(l.radiance - tau) / sigma);
      ++checked;
    }
    std::printf("channel %d: %d thresholds, worst |tau - true| %.3f sigma\n", c, checked, worst);
    EXPECT_GE(checked, 150);
    EXPECT_LT(worst, 0.15);
  }
}

TEST(Calibration, MergeIsConsistentAcrossExposuresAndMatchesTruth) {
  InverseResponse truth = *sim::BuiltinXtionProfile().response;
  sim::SimOptions o;
  o.width = 160;
  o.height = 120;
  o.sweep = true;
  o.sweep_exposures_ms = {0.25, 1, 4, 16, 64};
  o.sweep_repeats = 1;  // the built-in Xtion noise
  sim::SyntheticSource src(o);
  Sweep s;
  RadianceImage truth_L;
  while (!src.done()) {
    sim::SimFrame f = src.Next();
    s.images.push_back(std::move(f.color));
    s.exposure_ms.push_back(f.exposure_ms);
    truth_L = std::move(f.radiance);
  }
  const RadianceImage merged = MergeHdr(s, truth, *sim::BuiltinXtionProfile().noise);
  std::vector<double> err;
  for (std::size_t p = 0; p < merged.size(); ++p)
    if (truth_L[p].y > 0 && truth_L[p].y * 64 < 19.f)  // measurable in some exposure
      err.push_back(std::abs(std::log2(merged[p].y / truth_L[p].y)));
  std::nth_element(err.begin(), err.begin() + long(err.size() / 2), err.end());
  std::printf("merged radiance against truth: median |error| %.4f stops over %zu pixels\n",
              err[err.size() / 2], err.size());
  EXPECT_LT(err[err.size() / 2], 0.03);
  for (const auto& e : MergeConsistency(s, truth, merged)) {
    std::printf("  exposure %6.2f ms: median |deviation| %.4f stops (%ld samples)\n",
                e.exposure_ms, e.median_abs_stops, e.samples);
    EXPECT_LT(e.median_abs_stops, 0.05);
  }
}

TEST(Calibration, PcfFamilyFollowsThePaper) {
  const SensorInfo xt = sim::BuiltinXtionProfile();
  const PcfTables p = ComputePcf(*xt.response, *xt.noise);
  float hi = 0;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) {
      hi = std::max(hi, p[2][c][i]);
      EXPECT_FLOAT_EQ(p[0][c][i], 1.f);
      EXPECT_NEAR(p[1][c][i], std::sqrt(p[2][c][i]), 1e-6);
      EXPECT_NEAR(p[3][c][i], p[2][c][i] * p[2][c][i], 1e-6);
    }
  EXPECT_FLOAT_EQ(hi, 1.f);  // normalised by its maximum m
  // Low near saturation (f' -> 0), high in the mid-tones.
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(p[2][c][254], 0.1f * p[2][c][128]);
    EXPECT_GT(p[2][c][128], 0.3f);
  }
  // f' is the reciprocal slope of the inverse table.
  const LevelTable d = ResponseDerivative(*xt.response);
  EXPECT_NEAR(d[1][100], 2.0 / (xt.response->table[1][101] - xt.response->table[1][99]), 1e-3);
}

TEST(Calibration, EnforceMonotonicPoolsViolators) {
  InverseResponse r;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) r.table[c][i] = float(i) / 128.f;
  r.table[0][50] = 0.5f;  // a spike down: 50/128 = 0.39 expected
  r.table[0][51] = 0.2f;
  EnforceMonotonic(r);
  for (int i = 1; i < 256; ++i) ASSERT_GE(r.table[0][i], r.table[0][i - 1]);
  EXPECT_NEAR(r.table[0][50], r.table[0][51], 1e-6);
  EXPECT_FLOAT_EQ(r.table[0][128], 1.f);
}

TEST(Calibration, BadSweepsAreRefusedWithAReason) {
  const InverseResponse truth = *sim::BuiltinXtionProfile().response;
  Sweep one = SimulateSweep(truth, kTestNoise, 2, 64, 48);
  for (double& e : one.exposure_ms) e = 8;
  test::ExpectErrorContaining([&] { FitDebevec(one); }, {"single exposure", "8 ms"});

  Sweep saturated = SimulateSweep(truth, kTestNoise, 1, 64, 48);
  for (auto& im : saturated.images)
    for (std::size_t p = 0; p < im.size(); ++p) im[p] = {255, 255, 255};
  test::ExpectErrorContaining([&] { FitRobertson(saturated); }, {"clipped"});

  // The camera moved: the second half of the frames is shifted by 9 pixels.
  Sweep moved = SimulateSweep(truth, kTestNoise, 1, 96, 72);
  for (std::size_t j = moved.images.size() / 2; j < moved.images.size(); ++j) {
    ColorImage shifted(96, 72);
    for (int y = 0; y < 72; ++y)
      for (int x = 0; x < 96; ++x) shifted(x, y) = moved.images[j](std::min(95, x + 9), y);
    moved.images[j] = std::move(shifted);
  }
  test::ExpectErrorContaining([&] { FitDebevec(moved); }, {"moved"});
  // The unshifted sweep passes the same check.
  EXPECT_NO_THROW(CheckSweep(SimulateSweep(truth, kTestNoise, 1, 96, 72)));

  Sweep no_repeats = SimulateSweep(truth, kTestNoise, 1, 64, 48);
  test::ExpectErrorContaining([&] { FitNoise(no_repeats, truth); }, {"3 frames per exposure"});
}

// Noise is not motion: near black, a steep measured response turns sensor noise into many
// levels (DoRF 159: +-10 levels over its lower half), and single pixels of the 0.25 and
// 0.35 ms frames disagreed on their order in 6-13 % of pairs with no motion at all; such
// sweeps were refused as "moved" until the order test moved to 4 x 4 block means. The
// 9-pixel shift above is still caught.
TEST(Calibration, SteepToeNoiseIsNotMotion) {
  const auto file = test::SharedData("dorf/dorf_invI_201x1024.txt");
  HDRF_SKIP_WITHOUT(file, "dorf/dorf_invI_201x1024.txt");
  const auto rows = experiments::LoadDorfInverseCurves(file);
  for (int k : {14, 25})
    EXPECT_NO_THROW(CheckSweep(SimulateSweep(DorfTriplet(rows, k, k + 67, k + 134), kTestNoise))) << k;
}

TEST(Calibration, EmorBasisFileErrorsNamed) {
  test::TempDir dir;
  test::WriteText(dir / "bad.txt", "B = \n0 1 2\n");
  test::ExpectErrorContaining([&] { EmorBasis::Load(dir / "bad.txt"); }, {"bad.txt", "expected B, g0"});
  test::ExpectErrorContaining([&] { EmorBasis::Load(dir / "none.txt"); }, {"none.txt", "missing"});
  // Named where a file is expected: /dev/zero grew past 4 GB and a FIFO hung the reader; both
  // are refused at once, as every input file is.
  test::ExpectErrorContaining([&] { EmorBasis::Load("/dev/zero"); }, {"/dev/zero", "not a regular file"});
  ASSERT_EQ(::mkfifo((dir / "pipe.txt").c_str(), 0644), 0);
  test::ExpectErrorContaining([&] { EmorBasis::Load(dir / "pipe.txt"); }, {"pipe.txt", "not a regular file"});
  test::WriteText(dir / "big.txt", std::string(5 << 20, '1'));
  test::ExpectErrorContaining([&] { EmorBasis::Load(dir / "big.txt"); }, {"big.txt", "more than the"});
}

}  // namespace
}  // namespace hdrf::radiometry
