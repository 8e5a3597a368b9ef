#include "exposure/exposure.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace hdrf::exposure {

void ExposureOptions::Check() const {
  if (stride < 1 || stride > 16) throw SettingError("exposure.stride", "must be 1 to 16 pixels");
  if (min_samples < 1) throw SettingError("exposure.min_samples", "must be at least 1");
}

ExposureEstimate EstimateExposureRatio(const Image<Float3>& model_vertex_w,
                                       const RadianceImage& model_radiance,
                                       const RadianceImage& live_radiance,
                                       const Image<float>& live_conf, const PinholeCamera& cam,
                                       const Pose& T_world_live, const ExposureOptions& o) {
  const ExposureArgs a{View(model_vertex_w), View(model_radiance), View(live_radiance),
                       View(live_conf), cam, ToRigidTransform(T_world_live.inverse())};
  std::vector<std::pair<float, float>> samples;  // (log ratio, weight)
  for (int y = 0; y < model_vertex_w.height(); y += o.stride)
    for (int x = 0; x < model_vertex_w.width(); x += o.stride) {
      float lr, w;
      if (ExposureSample(a, x, y, &lr, &w)) samples.emplace_back(lr, w);
    }
  return WeightedMedianRatio(samples, o.min_samples);
}

ExposureEstimate WeightedMedianRatio(std::vector<std::pair<float, float>>& samples, int min_samples) {
  ExposureEstimate e;
  e.samples = long(samples.size());
  if (long(samples.size()) < min_samples) return e;
  std::sort(samples.begin(), samples.end());
  double total = 0;
  for (auto& s : samples) total += s.second;
  double acc = 0;
  for (auto& s : samples) {
    acc += s.second;
    if (acc >= 0.5 * total) {
      e.log_ratio = s.first;
      e.ratio = std::exp(double(s.first));
      break;
    }
  }
  e.valid = true;
  return e;
}

}  // namespace hdrf::exposure
