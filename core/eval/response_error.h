// Accuracy of a recovered camera response against a known one: the two error figures the
// calibration tests, the calibration wizard's synthetic runs and the experiments report.
#pragma once

#include <algorithm>
#include <array>

#include "radiometry/response.h"

namespace hdrf::eval {

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

}  // namespace hdrf::eval
