// Accuracy of a recovered camera response against a known one: the real measured curves of
// Grossberg & Nayar's DoRF database as truth, simulated exposure sweeps through them, and the
// two error figures the calibration tests and `bench --suite calibration` report.
#pragma once

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "radiometry/calibration.h"

namespace hdrf::eval {

// dorf_invI_201x1024.txt: one inverse response per line (irradiance at brightness
// B = j / 1023, 1024 values rising from 0 to 1); '#' lines are comments. Throws InputError
// naming the file and line for a missing file, a short row or a non-finite value.
std::vector<std::vector<double>> LoadDorfInverseCurves(const std::filesystem::path& file);

// A TUM-monoVO / DSO pcalib.txt (256 numbers, the inverse response of an 8-bit camera), as
// the same curve in all three channels scaled so that f^-1(128) = 1. Throws InputError naming
// the file for a missing file, a value that is not a number, or a count other than 256.
radiometry::InverseResponse LoadPcalibResponse(const std::filesystem::path& file);

// The sensor noise of the calibration tests and `bench --suite calibration`: a consumer
// sensor at base gain, in units of f^-1(128) = 1.
inline const radiometry::NoiseModel kSweepNoise{{0.030f, 0.025f, 0.035f}, {0.020f, 0.015f, 0.025f}};

// A 256-level inverse response from sampled curves (one per channel, any length >= 2),
// linearly interpolated at B = i / 255, scaled so that f^-1(128) = 1. A ramp of 1e-4 of the range
// keeps flat runs of the measured table strictly increasing.
radiometry::InverseResponse InverseFromCurves(const std::array<const std::vector<double>*, 3>& curves);

// Error of `estimate` against `truth` over levels lo..hi, after the best scale per channel
// (least squares over those levels), as shares of the true full range f^-1(255) - f^-1(0):
// - point: |s f^-1_est(i) - f^-1_true(i)|, the largest over the levels;
// - bin:   the distance of s f^-1_est(i) from the radiances the true camera maps to level i
//          (the simulated sensor thresholds midway between table values): 0 when the
//          estimate maps back to level i. Where the measured curve jumps (a flat stretch of
//          the forward response) one level covers a wide band of radiance, and only this
//          figure says whether an estimate is consistent with the camera.
struct ResponseAccuracy {
  std::array<double, 3> point{}, bin{};
  std::array<int, 3> point_level{}, bin_level{};  // where the largest error is
  std::array<double, 3> widest_bin{};             // widest level band over lo..hi, share of range
  double PointMax() const { return std::max({point[0], point[1], point[2]}); }
  double BinMax() const { return std::max({bin[0], bin[1], bin[2]}); }
};
ResponseAccuracy CompareResponse(const radiometry::InverseResponse& estimate,
                                 const radiometry::InverseResponse& truth, int lo = 5, int hi = 250);

// A static-camera exposure sweep of a built-in synthetic scene ("room" or "desk") through
// `truth`: half-stop exposures from 0.25 to 128 ms (19), `repeats` frames each.
radiometry::Sweep SimulateSweep(const radiometry::InverseResponse& truth,
                                const radiometry::NoiseModel& noise, int repeats = 2,
                                int width = 160, int height = 120,
                                const std::string& scene = "room");

}  // namespace hdrf::eval
