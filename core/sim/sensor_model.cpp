#include "sim/sensor_model.h"

#include <algorithm>
#include <limits>

namespace hdrf::sim {

ForwardResponse::ForwardResponse(const radiometry::InverseResponse& inverse) {
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 255; ++i)
      thresholds_[c][i] = 0.5f * (inverse.table[c][i] + inverse.table[c][i + 1]);
    thresholds_[c][255] = std::numeric_limits<float>::infinity();
  }
}

std::uint8_t ForwardResponse::Level(int c, float R) const {
  // Number of thresholds <= R (as upper_bound), by an 8-step branch-free search.
  const float* t = thresholds_[c].data();
  int lo = 0;
  for (int step = 128; step > 0; step >>= 1) lo += (t[lo + step - 1] <= R) ? step : 0;
  return std::uint8_t(lo);
}

float AxialSigma(float z_m) {
  // Nguyen, Izadi & Lovell (3DIMPVT 2012): sigma_z = 0.0012 + 0.0019 (z - 0.4)^2.
  const float d = z_m - 0.4f;
  return 0.0012f + 0.0019f * d * d;
}

}  // namespace hdrf::sim
