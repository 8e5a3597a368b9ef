// Camera response tables and the image formation model (docs/dev/architecture.md, "The method").
#pragma once

#include <array>
#include <string>

namespace hdrf::radiometry {

inline constexpr int kLevels = 256;

// f^-1(I) per channel for I = 0..255, in linear radiance units R = L * exposure_ms.
// Monotonically non-decreasing per channel (Check() enforces it).
struct InverseResponse {
  std::array<std::array<float, kLevels>, 3> table{};  // [channel][level]

  // Throws hdrf::Error naming `source` (a file or setting) and the first offending
  // channel and level: non-finite values, negative values or a decreasing step.
  void Check(const std::string& source) const;

  // Contiguous channel-major copy (r[0..255], g[..], b[..]) for kernels.
  std::array<float, 3 * kLevels> Flat() const;

  // sRGB transfer function scaled so that level 255 maps to 1: the documented fallback
  // when a sequence carries no calibration (`--response srgb`).
  static InverseResponse Srgb();
};

// Image formation noise: I = f(R + n_s + n_c), Var(n_s) = R * sigma_s^2, Var(n_c) = sigma_c^2.
struct NoiseModel {
  std::array<float, 3> sigma_s{};
  std::array<float, 3> sigma_c{};
  void Check(const std::string& source) const;
};

}  // namespace hdrf::radiometry
