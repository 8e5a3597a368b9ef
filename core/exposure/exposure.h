// Exposure compensation after tracking (the paper's step 5). Tracking never needs the
// exposure (normalized radiance does not depend on it); once the pose is known, the ratio t
// of the model's radiance to the live frame's brings the live radiance into model units
// before it is fused.
#pragma once

#include <utility>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "exposure/exposure_impl.h"

namespace hdrf::exposure {

// Exposure ratio t of the live frame against the model (model radiance = t * live
// radiance): the confidence-weighted median over matched pixels of the luminance ratio,
// leaving out saturated or black live pixels and pixels without model radiance.
struct ExposureOptions {
  int stride = 2;         // every stride-th pixel in x and y is a sample
  int min_samples = 50;   // fewer matched samples: no estimate (the ratio stays 1)
  void Check() const;     // throws SettingError naming the setting
};
struct ExposureEstimate {
  double ratio = 1;
  float log_ratio = 0;  // the median sample's log ratio (ratio = exp of it)
  long samples = 0;
  bool valid = false;
};
ExposureEstimate EstimateExposureRatio(const Image<Float3>& model_vertex_w,
                                       const RadianceImage& model_radiance,
                                       const RadianceImage& live_radiance,
                                       const Image<float>& live_confidence,
                                       const PinholeCamera& cam, const Pose& T_world_live,
                                       const ExposureOptions& o = {});
// The confidence-weighted median of (log ratio, weight) samples (sorted in place); invalid
// below min_samples samples.
ExposureEstimate WeightedMedianRatio(std::vector<std::pair<float, float>>& samples, int min_samples = 50);

}  // namespace hdrf::exposure
