// Keyframes: the frames a scan keeps for texturing its model afterwards. A fused frame
// becomes a keyframe when the camera has moved or turned enough since the last one; the
// colour is kept as the sensor delivered it (8-bit), with its pose and the exposure ratio
// the engine estimated, so that the texture can be baked from radiance in the model's
// units later (hdrfusion export, the studio's Export dialog).
#pragma once

#include <vector>

#include "common/image.h"
#include "common/se3.h"
#include "mesh/texture_bake.h"
#include "pipeline/pipeline.h"
#include "radiometry/sensor.h"

namespace hdrf::pipeline {

struct Keyframe {
  int index = 0;                         // frame index in the scan
  double timestamp = 0;
  Pose T_world_camera = Pose::Identity();
  double exposure_ratio = 1;             // model radiance / this frame's radiance
  ColorImage color;
};

struct KeyframeOptions {
  bool enabled = true;
  double min_translation_m = 0.08;  // a new keyframe after this much motion...
  double min_rotation_deg = 8;      // ...or this much turning since the last one
  int max_keyframes = 150;          // beyond it the set is thinned (every other one) and the steps doubled
  void Check() const;               // throws SettingError naming the option
};

class KeyframeSelector {
 public:
  explicit KeyframeSelector(const KeyframeOptions& o = {});
  // Keeps the frame if it was fused and is far enough from the last keyframe.
  bool Offer(const FrameReport& report, const ColorImage& color);
  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  int thinned() const { return thinned_; }  // how many times the set was halved
  // Takes up a saved set (a project reopened): its keyframes and how often it was halved.
  void Restore(std::vector<Keyframe> keyframes, int thinned);

 private:
  KeyframeOptions o_;
  double step_m_, step_deg_;
  std::vector<Keyframe> keyframes_;
  int thinned_ = 0;
};

// Bake views: each keyframe's radiance through the sensor's response, in the model's units
// (times its exposure ratio), with the confidence the engine fuses with (PCF p_k).
std::vector<mesh::BakeView> MakeBakeViews(const std::vector<Keyframe>& keyframes, const SensorInfo& sensor,
                                          int pcf_power);

}  // namespace hdrf::pipeline
