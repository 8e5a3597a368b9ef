// The derivative of the camera response and the pixel confidence function (PCF) family of
// the paper: p(I) = f'(R) sqrt(R sigma_s^2 + sigma_c^2) / m, R = f^-1(I), with m the
// largest value of f'(R) sqrt(...) over all levels and the three channels (so p is in
// (0, 1]); p0 = 1, p1 = sqrt(p), p2 = p, p3 = p^2.
#pragma once

#include <array>

#include "radiometry/response.h"

namespace hdrf::radiometry {

using LevelTable = std::array<std::array<float, kLevels>, 3>;  // [channel][level]

// f'(R) at R = f^-1(I): levels per unit radiance, from central differences of the
// inverse table (one-sided at 0 and 255; 0 where the inverse is locally flat... never:
// a flat step gives the largest finite slope of its neighbours).
LevelTable ResponseDerivative(const InverseResponse& inverse);

struct PcfTables {
  std::array<LevelTable, 4> p;  // p[k][channel][level], k = 0..3
  float m = 1;                  // the normaliser
  const LevelTable& operator[](int k) const { return p[std::size_t(k)]; }
};

PcfTables ComputePcf(const InverseResponse& inverse, const NoiseModel& noise);

// The noise model used when a sensor has none calibrated: a mild floor from the response
// alone (sigma_s = 0.02, sigma_c = 0.2 % of mid-grey radiance), documented in docs/engine.md.
NoiseModel DefaultNoise(const InverseResponse& inverse);

}  // namespace hdrf::radiometry
