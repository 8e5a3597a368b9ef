#include "eval/response_error.h"

#include <cmath>

#include "radiometry/calibration.h"

namespace hdrf::eval {

ResponseAccuracy CompareResponse(const radiometry::InverseResponse& est,
                                 const radiometry::InverseResponse& truth, int lo, int hi) {
  ResponseAccuracy a;
  for (int c = 0; c < 3; ++c) {
    const auto& t = truth.table[c];
    const auto& e = est.table[c];
    const double s = radiometry::ScaleOnto(est, truth, c, lo, hi);
    const double range = t[255] - t[0];
    for (int i = lo; i <= hi; ++i) {
      const double v = s * e[i];
      const double point = std::abs(v - t[i]) / range;
      const double band_lo = i > 0 ? 0.5 * (t[i - 1] + t[i]) : t[0];
      const double band_hi = i < 255 ? 0.5 * (t[i] + t[i + 1]) : t[255];
      const double bin = std::max({band_lo - v, v - band_hi, 0.0}) / range;
      if (point > a.point[c]) a.point[c] = point, a.point_level[c] = i;
      if (bin > a.bin[c]) a.bin[c] = bin, a.bin_level[c] = i;
      a.widest_bin[c] = std::max(a.widest_bin[c], (band_hi - band_lo) / range);
    }
  }
  return a;
}

}  // namespace hdrf::eval
