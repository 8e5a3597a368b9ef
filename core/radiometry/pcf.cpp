#include "radiometry/pcf.h"

#include <algorithm>
#include <cmath>

namespace hdrf::radiometry {

LevelTable ResponseDerivative(const InverseResponse& inverse) {
  LevelTable d{};
  for (int c = 0; c < 3; ++c) {
    const auto& t = inverse.table[c];
    for (int i = 0; i < kLevels; ++i) {
      const int lo = std::max(0, i - 1), hi = std::min(kLevels - 1, i + 1);
      const float dr = t[hi] - t[lo];
      d[c][i] = dr > 0 ? float(hi - lo) / dr : 0.f;
    }
    // Flat runs (dr == 0) inherit the slope of the nearest level with one.
    for (int i = 0; i < kLevels; ++i)
      if (d[c][i] == 0.f)
        for (int k = 1; k < kLevels; ++k) {
          if (i - k >= 0 && d[c][i - k] > 0) { d[c][i] = d[c][i - k]; break; }
          if (i + k < kLevels && d[c][i + k] > 0) { d[c][i] = d[c][i + k]; break; }
        }
  }
  return d;
}

PcfTables ComputePcf(const InverseResponse& inverse, const NoiseModel& noise) {
  const LevelTable d = ResponseDerivative(inverse);
  LevelTable raw{};
  float m = 0;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kLevels; ++i) {
      const float R = inverse.table[c][i];
      raw[c][i] = d[c][i] * std::sqrt(R * noise.sigma_s[c] * noise.sigma_s[c] +
                                      noise.sigma_c[c] * noise.sigma_c[c]);
      m = std::max(m, raw[c][i]);
    }
  PcfTables out;
  out.m = m > 0 ? m : 1.f;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kLevels; ++i) {
      const float p = raw[c][i] / out.m;
      out.p[0][c][i] = 1.f;
      out.p[1][c][i] = std::sqrt(p);
      out.p[2][c][i] = p;
      out.p[3][c][i] = p * p;
    }
  return out;
}

NoiseModel DefaultNoise(const InverseResponse& inverse) {
  NoiseModel noise;
  noise.sigma_s = {0.02f, 0.02f, 0.02f};
  for (int c = 0; c < 3; ++c) noise.sigma_c[std::size_t(c)] = 0.002f * inverse.table[std::size_t(c)][128];
  return noise;
}

}  // namespace hdrf::radiometry
