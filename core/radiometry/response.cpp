#include "radiometry/response.h"

#include <cmath>

#include "common/error.h"

namespace hdrf::radiometry {

namespace {
const char* kChannel[3] = {"r", "g", "b"};
}

void InverseResponse::Check(const std::string& source) const {
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < kLevels; ++i) {
      const float v = table[c][i];
      if (!std::isfinite(v))
        throw Error(source + ": response channel " + kChannel[c] + " level " + std::to_string(i) +
                    " is not a finite number");
      if (v < 0.f)
        throw Error(source + ": response channel " + kChannel[c] + " level " + std::to_string(i) +
                    " is negative (" + std::to_string(v) + ")");
      if (i > 0 && v < table[c][i - 1])
        throw Error(source + ": response channel " + kChannel[c] +
                    " is not monotonically non-decreasing at level " + std::to_string(i) + " (" +
                    std::to_string(table[c][i - 1]) + " then " + std::to_string(v) + ")");
    }
    if (!(table[c][kLevels - 1] > table[c][0]))
      throw Error(source + ": response channel " + kChannel[c] + " is constant");
  }
}

std::array<float, 3 * kLevels> InverseResponse::Flat() const {
  std::array<float, 3 * kLevels> out{};
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kLevels; ++i) out[c * kLevels + i] = table[c][i];
  return out;
}

InverseResponse InverseResponse::Srgb() {
  InverseResponse r;
  for (int i = 0; i < kLevels; ++i) {
    const double v = i / 255.0;
    const double lin = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    for (int c = 0; c < 3; ++c) r.table[c][i] = float(lin);
  }
  return r;
}

void NoiseModel::Check(const std::string& source) const {
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(sigma_s[c]) || sigma_s[c] < 0.f || !std::isfinite(sigma_c[c]) ||
        sigma_c[c] < 0.f)
      throw Error(source + ": noise sigma_s/sigma_c of channel " + kChannel[c] +
                  " must be finite and non-negative");
  }
}

}  // namespace hdrf::radiometry
