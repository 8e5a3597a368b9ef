// The simulated sensor: image formation I = f(R + n_s + n_c) with R = L * exposure_ms,
// Var(n_s) = R * sigma_s^2, Var(n_c) = sigma_c^2, 8-bit quantisation and clipping per
// channel; Kinect-like depth (axial noise growing with z^2, disparity quantisation,
// dropout at grazing angles, near depth edges and on emitters, range limits).
#pragma once

#include <array>
#include <cstdint>

#include "common/image.h"
#include "radiometry/response.h"

namespace hdrf::sim {

// The camera response f (forward), from an inverse response table: the 8-bit level whose
// inverse value is nearest in radiance, i.e. thresholds at the midpoints between levels.
class ForwardResponse {
 public:
  explicit ForwardResponse(const radiometry::InverseResponse& inverse);
  // Level 0..255 of radiance R (R = L * exposure_ms) on channel c.
  std::uint8_t Level(int c, float R) const;

 private:
  // 255 midpoints padded with +inf to 256 for a branch-free binary search.
  std::array<std::array<float, 256>, 3> thresholds_{};
};

struct DepthNoiseOptions {
  bool enabled = true;          // false: exact depth (still range-limited)
  float min_m = 0.4f;           // closer: no data
  float max_m = 4.5f;           // farther: no data
  float baseline_m = 0.075f;    // projector-camera baseline
  float focal_px = 580.f;       // focal length of the VGA depth camera (quantisation)
  float subpixel = 8.f;         // disparity steps per pixel
  float grazing_cos = 0.2f;     // |n.v| below this: dropped (about 78 degrees)
  float edge_jump = 0.04f;      // relative depth jump to a neighbour that marks an edge
  float edge_dropout = 0.5f;    // probability of dropping an edge pixel
};

// Axial standard deviation of a Kinect-class sensor at depth z (metres).
float AxialSigma(float z_m);

}  // namespace hdrf::sim
