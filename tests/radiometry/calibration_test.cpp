// Calibration against known truth: simulated sweeps through real measured response curves
// (the built-in Xtion profile always; DoRF, EMoR and BorealHDR curves from ../shared/data
// where present), then the real Memorial sweep (tests/io).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "radiometry/calibration.h"
#include "radiometry/pcf.h"
#include "sim/builtin_sensor.h"
#include "sim/synthetic_source.h"
#include "support/test_support.h"

namespace hdrf::radiometry {
namespace {

}  // namespace
void NormaliseForTest(InverseResponse& r);
namespace {

const NoiseModel kTestNoise{{0.030f, 0.025f, 0.035f}, {0.020f, 0.015f, 0.025f}};

// A half-stop sweep from 0.25 to 128 ms (19 exposures), as calibrate's report recommends.
Sweep SimulatedSweep(const InverseResponse& truth, const NoiseModel& noise, int repeats = 2,
                     int width = 160, int height = 120) {
  sim::SimOptions o;
  o.width = width;
  o.height = height;
  o.sweep = true;
  o.sweep_exposures_ms.clear();
  for (int k = 0; k <= 18; ++k) o.sweep_exposures_ms.push_back(0.25 * std::pow(2.0, k / 2.0));
  o.sweep_repeats = repeats;
  o.response = truth;
  o.noise = noise;
  sim::SyntheticSource src(o);
  Sweep s;
  s.source = "simulated sweep";
  while (!src.done()) {
    sim::SimFrame f = src.Next();
    s.images.push_back(std::move(f.color));
    s.exposure_ms.push_back(f.exposure_ms);
  }
  return s;
}

// Best scale per channel (least squares over levels 5..250), then the largest error over
// those levels as a share of the true full range. Returns the worst channel; scale[c] gets
// the factor that maps the estimate onto the truth.
double RangeError(const InverseResponse& est, const InverseResponse& truth,
                  std::array<double, 3>* scale = nullptr) {
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    double num = 0, den = 0;
    for (int i = 5; i <= 250; ++i) {
      num += double(est.table[c][i]) * truth.table[c][i];
      den += double(est.table[c][i]) * est.table[c][i];
    }
    const double s = num / den;
    if (scale) (*scale)[c] = s;
    const double range = truth.table[c][255] - truth.table[c][0];
    for (int i = 5; i <= 250; ++i)
      worst = std::max(worst, std::abs(s * est.table[c][i] - truth.table[c][i]) / range);
  }
  return worst;
}

// DoRF inverse curves: row k gives irradiance at brightness B_j = j / 1023.
InverseResponse DorfCurves(const std::filesystem::path& file, int k_r, int k_g, int k_b) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    rows.emplace_back();
    double v;
    while (ss >> v) rows.back().push_back(v);
  }
  InverseResponse r;
  const int ks[3] = {k_r, k_g, k_b};
  for (int c = 0; c < 3; ++c) {
    const auto& row = rows.at(std::size_t(ks[c]));
    for (int i = 0; i < 256; ++i) {
      const double x = i * 1023.0 / 255.0;
      const int j = std::min(1022, int(x));
      // A tiny ramp keeps flat runs of the quantised table strictly increasing.
      r.table[c][i] = float(row[std::size_t(j)] + (row[std::size_t(j + 1)] - row[std::size_t(j)]) * (x - j) + 1e-4 * i / 255.0);
    }
  }
  NormaliseForTest(r);
  return r;
}

}  // namespace

// Scale a truth table like the fits are scaled (f^-1(128) = 1), so noise units match.
void NormaliseForTest(InverseResponse& r) {
  for (int c = 0; c < 3; ++c) {
    const float s = r.table[c][128];
    for (float& v : r.table[c]) v /= s;
  }
}

namespace {

// The target is 1 % of full range over levels 5..250. Debevec and Robertson meet it on the
// Xtion, BorealHDR and most DoRF curves; two known gaps are asserted at what they measure
// today, so a regression still fails (docs/calibration.md, "Known gaps"):
// - EMoR, whose low-order basis cannot follow steep knees at levels 245-250 (Xtion: not
//   claimed at all; DoRF: within 5 %),
// - DoRF curve 130, whose last 5 levels rise by 35 % of its range (within 4 %).
void CheckMethods(const InverseResponse& truth, const char* name, bool with_emor,
                  bool emor_claimed = true, double classic_tolerance = 0.01,
                  double emor_tolerance = 0.05) {
  const Sweep s = SimulatedSweep(truth, kTestNoise);
  const ResponseFit deb = FitDebevec(s);
  const ResponseFit rob = FitRobertson(s);
  const double e_deb = RangeError(deb.inverse, truth), e_rob = RangeError(rob.inverse, truth);
  std::printf("%s: worst error over levels 5-250 as share of full range: debevec %.4f, robertson %.4f",
              name, e_deb, e_rob);
  EXPECT_LT(e_deb, classic_tolerance) << name;
  EXPECT_LT(e_rob, classic_tolerance) << name;
  if (with_emor) {
    const auto basis_file = test::SharedData("emor/invemor.txt");
    if (!basis_file.empty()) {
      const ResponseFit em = FitEmor(s, EmorBasis::Load(basis_file));
      const double e_em = RangeError(em.inverse, truth);
      std::printf(", emor %.4f%s", e_em, emor_claimed ? "" : " (not claimed)");
      if (emor_claimed) EXPECT_LT(e_em, emor_tolerance) << name;
    }
  }
  std::printf("\n");
  for (const auto* fit : {&deb, &rob})
    for (int c = 0; c < 3; ++c) {
      EXPECT_FLOAT_EQ(fit->inverse.table[c][128], 1.0f);  // the documented scale
      for (int i = 1; i < 256; ++i) ASSERT_GE(fit->inverse.table[c][i], fit->inverse.table[c][i - 1]);
    }
}

TEST(Calibration, RecoversTheXtionResponse) {
  CheckMethods(*sim::BuiltinXtionProfile().response, "xtion", true, false);
}

TEST(Calibration, RecoversDorfResponses) {
  const auto file = test::SharedData("dorf/dorf_invI_201x1024.txt");
  HDRF_SKIP_WITHOUT(file, "dorf/dorf_invI_201x1024.txt");
  for (int k : {0, 57, 123, 190}) {
    const std::string name = "dorf " + std::to_string(k) + "/" + std::to_string(k + 3) + "/" + std::to_string(k + 7);
    CheckMethods(DorfCurves(file, k, k + 3, k + 7), name.c_str(), true, true,
                 k == 123 ? 0.04 : 0.01);
  }
}

TEST(Calibration, RecoversBorealHdrMeasuredResponse) {
  const auto file = test::SharedData("camera_response_measured/borealhdr_pcalib_inside1.txt");
  HDRF_SKIP_WITHOUT(file, "camera_response_measured/borealhdr_pcalib_inside1.txt");
  std::ifstream in(file);
  InverseResponse r;
  for (int i = 0; i < 256; ++i) {
    double v;
    ASSERT_TRUE(in >> v);
    for (int c = 0; c < 3; ++c) r.table[c][i] = float(v);
  }
  NormaliseForTest(r);
  CheckMethods(r, "borealhdr", false);
}

TEST(Calibration, NoiseLevelFunctionWithinTenPercent) {
  // Truth in the calibration's own units (f^-1(128) = 1), so the sigmas compare directly.
  InverseResponse truth = *sim::BuiltinXtionProfile().response;
  NormaliseForTest(truth);
  const Sweep s = SimulatedSweep(truth, kTestNoise, 6);
  const ResponseFit fit = FitDebevec(s);
  const NoiseFit nf = FitNoise(s, fit.inverse);
  for (int c = 0; c < 3; ++c) {
    const double ss = nf.noise.sigma_s[c], sc = nf.noise.sigma_c[c];
    std::printf("channel %d: sigma_s %.4f (true %.4f), sigma_c %.4f (true %.4f), %zu levels, "
                "fit residual %.3f\n", c, ss, kTestNoise.sigma_s[c], sc, kTestNoise.sigma_c[c],
                nf.levels[c].size(), nf.rms_relative_residual[c]);
    EXPECT_NEAR(ss, kTestNoise.sigma_s[c], 0.1 * kTestNoise.sigma_s[c]);
    EXPECT_NEAR(sc, kTestNoise.sigma_c[c], 0.1 * kTestNoise.sigma_c[c]);
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
  Sweep one = SimulatedSweep(truth, kTestNoise, 2, 64, 48);
  for (double& e : one.exposure_ms) e = 8;
  test::ExpectErrorContaining([&] { FitDebevec(one); }, {"single exposure", "8 ms"});

  Sweep saturated = SimulatedSweep(truth, kTestNoise, 1, 64, 48);
  for (auto& im : saturated.images)
    for (std::size_t p = 0; p < im.size(); ++p) im[p] = {255, 255, 255};
  test::ExpectErrorContaining([&] { FitRobertson(saturated); }, {"clipped"});

  // The camera moved: the second half of the frames is shifted by 9 pixels.
  Sweep moved = SimulatedSweep(truth, kTestNoise, 1, 96, 72);
  for (std::size_t j = moved.images.size() / 2; j < moved.images.size(); ++j) {
    ColorImage shifted(96, 72);
    for (int y = 0; y < 72; ++y)
      for (int x = 0; x < 96; ++x) shifted(x, y) = moved.images[j](std::min(95, x + 9), y);
    moved.images[j] = std::move(shifted);
  }
  test::ExpectErrorContaining([&] { FitDebevec(moved); }, {"moved"});
  // The unshifted sweep passes the same check.
  EXPECT_NO_THROW(CheckSweep(SimulatedSweep(truth, kTestNoise, 1, 96, 72)));

  Sweep no_repeats = SimulatedSweep(truth, kTestNoise, 1, 64, 48);
  test::ExpectErrorContaining([&] { FitNoise(no_repeats, truth); }, {"3 frames per exposure"});
}

TEST(Calibration, EmorBasisFileErrorsNamed) {
  test::TempDir dir;
  test::WriteText(dir / "bad.txt", "B = \n0 1 2\n");
  test::ExpectErrorContaining([&] { EmorBasis::Load(dir / "bad.txt"); }, {"bad.txt", "expected B, g0"});
  test::ExpectErrorContaining([&] { EmorBasis::Load(dir / "none.txt"); }, {"none.txt", "missing"});
}

}  // namespace
}  // namespace hdrf::radiometry
