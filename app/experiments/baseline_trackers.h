// Frame-to-frame trackers of the evaluation that the engine itself does not use: the
// published alternatives to normalized radiance for tracking under exposure changes.
//
// - NCC (after Scandaroli, Meilland & Richa, ECCV 2012): each pixel's raw 8-bit intensity
//   is normalized by the mean and standard deviation of its small square patch (9x9 by
//   default), which is the per-pixel linearization of patch-wise normalized
//   cross-correlation; tracked with the engine's photometric Gauss-Newton term, unweighted
//   (no response calibration, no confidence).
// - Joint exposure (after Meilland, Comport & Rives, BMVC 2011): radiance through the
//   calibrated response, and one global gain a = exp(b) estimated jointly with the pose in
//   a 7-parameter Gauss-Newton: r = L_ref(x) - a L_live(w(x)), weighted by the live PCF.
//
// Both align each frame to the previous one (coarse to fine), starting from a
// constant-velocity prediction, as their papers do against a reference image.
#pragma once

#include <memory>
#include <string>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "radiometry/sensor.h"
#include "tracking/tracking.h"

namespace hdrf::experiments {

enum class BaselineKind { kNcc, kJointExposure };

struct BaselineOptions {
  int levels = 3;
  std::array<int, 4> iterations = {10, 10, 8, 8};  // per level, coarsest first
  // NCC: side of the patch, pixels. 5x5 diverged on the synthetic Xtion even at a fixed
  // exposure (ATE 78 cm over 60 frames: the normalized image is mostly noise); 9x9 tracks.
  int ncc_patch = 9;
  float ncc_sigma = 0.25f;       // NCC: residual scale (normalized units)
  float ncc_min_std = 0.02f;     // NCC: floor on the patch std, relative to its mean (sensor noise)
  float gain_sigma = 0.1f;       // joint exposure: residual scale, relative to mean radiance
  float huber_k = 1.345f;
  int pcf = 1;                   // joint exposure: PCF variant for the weights
};

struct BaselineStep {
  Pose T_world_camera = Pose::Identity();
  double gain = 1;  // joint exposure: estimated L_ref / L_live radiance ratio (1 for NCC)
  int iterations = 0;
  bool lost = false;  // no usable system (the prediction was kept)
};

class BaselineTracker {
 public:
  BaselineTracker(BaselineKind kind, const PinholeCamera& camera, const SensorInfo& sensor,
                  const BaselineOptions& o = {});
  ~BaselineTracker();
  // The first frame defines the world frame (identity pose).
  BaselineStep Process(const ColorImage& color, const DepthImage& depth_m);

 private:
  struct State;
  std::unique_ptr<State> s_;
};

const char* BaselineName(BaselineKind k);

}  // namespace hdrf::experiments
