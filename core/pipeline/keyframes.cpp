#include "pipeline/keyframes.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.h"
#include "radiometry/pcf.h"
#include "radiometry/radiance.h"

namespace hdrf::pipeline {

void KeyframeOptions::Check() const {
  if (!(min_translation_m >= 0 && min_translation_m < 10))
    throw SettingError("keyframe translation", "must be 0 to 10 m, got " + std::to_string(min_translation_m));
  if (!(min_rotation_deg >= 0 && min_rotation_deg <= 180))
    throw SettingError("keyframe rotation", "must be 0 to 180 degrees, got " + std::to_string(min_rotation_deg));
  if (max_keyframes < 2 || max_keyframes > 10000)
    throw SettingError("max keyframes", "must be 2 to 10000, got " + std::to_string(max_keyframes));
}

KeyframeSelector::KeyframeSelector(const KeyframeOptions& o)
    : o_((o.Check(), o)), step_m_(o.min_translation_m), step_deg_(o.min_rotation_deg) {}

bool KeyframeSelector::Offer(const FrameReport& r, const ColorImage& color) {
  if (!o_.enabled || !r.fused) return false;
  if (!keyframes_.empty()) {
    const Pose d = keyframes_.back().T_world_camera.inverse() * r.T_world_camera;
    if (se3::TranslationNorm(d) < step_m_ && se3::RotationAngle(d) * 180.0 / M_PI < step_deg_) return false;
  }
  keyframes_.push_back({r.index, r.timestamp, r.T_world_camera, r.exposure_ratio, color.Clone()});
  if (int(keyframes_.size()) > o_.max_keyframes) {
    std::vector<Keyframe> kept;
    for (std::size_t i = 0; i < keyframes_.size(); i += 2) kept.push_back(std::move(keyframes_[i]));
    keyframes_ = std::move(kept);
    step_m_ = 2 * std::max(step_m_, 0.01);
    step_deg_ = 2 * std::max(step_deg_, 1.0);
    ++thinned_;
  }
  return true;
}

void KeyframeSelector::Restore(std::vector<Keyframe> keyframes, int thinned) {
  if (thinned < 0 || thinned > 30) throw Error("a keyframe set cannot have been halved " + std::to_string(thinned) + " times");
  keyframes_ = std::move(keyframes);
  thinned_ = thinned;
  step_m_ = o_.min_translation_m;
  step_deg_ = o_.min_rotation_deg;
  for (int i = 0; i < thinned; ++i) {
    step_m_ = 2 * std::max(step_m_, 0.01);
    step_deg_ = 2 * std::max(step_deg_, 1.0);
  }
}

std::vector<mesh::BakeView> MakeBakeViews(const std::vector<Keyframe>& keyframes, const SensorInfo& sensor,
                                          int pcf_power) {
  if (!sensor.response) throw Error("the scan's sensor has no response calibration: its frames cannot become radiance");
  if (pcf_power < 0 || pcf_power > 3) throw SettingError("pcf", "must be 0 to 3");
  const radiometry::InverseResponse& inverse = *sensor.response;
  const radiometry::PcfTables pcf =
      radiometry::ComputePcf(inverse, sensor.noise ? *sensor.noise : radiometry::DefaultNoise(inverse));
  for (std::size_t i = 0; i < keyframes.size(); ++i)
    if (keyframes[i].color.width() != sensor.camera.width || keyframes[i].color.height() != sensor.camera.height)
      throw Error("keyframe " + std::to_string(keyframes[i].index) + " is " + std::to_string(keyframes[i].color.width()) +
                  "x" + std::to_string(keyframes[i].color.height()) + ", the camera " +
                  std::to_string(sensor.camera.width) + "x" + std::to_string(sensor.camera.height));
  std::vector<mesh::BakeView> views(keyframes.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < int(keyframes.size()); ++i) {
    const Keyframe& k = keyframes[std::size_t(i)];
    mesh::BakeView& v = views[std::size_t(i)];
    v.T_world_camera = k.T_world_camera;
    v.camera = sensor.camera;
    Image<float> max_confidence;
    radiometry::ConvertFrame(k.color, inverse, pcf, pcf_power, v.radiance, v.confidence, max_confidence, Device::kCpu);
    const float s = float(k.exposure_ratio);
    for (std::size_t p = 0; p < v.radiance.size(); ++p) v.radiance[p] = v.radiance[p] * s;
  }
  return views;
}

}  // namespace hdrf::pipeline
