#include "exposure/exposure.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/parallel.h"

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
  // The rows of samples made side by side, each into its own stretch, then gathered in row
  // order: the samples a row-by-row loop makes, in its order.
  const int cols = (model_vertex_w.width() + o.stride - 1) / o.stride;
  const int rows = (model_vertex_w.height() + o.stride - 1) / o.stride;
  std::vector<std::pair<float, float>> samples(std::size_t(rows) * std::size_t(cols));  // (log ratio, weight)
  std::vector<int> made(std::size_t(rows), 0);
#pragma omp parallel for schedule(static)
  for (int r = 0; r < rows; ++r) {
    std::pair<float, float>* out = samples.data() + std::size_t(r) * std::size_t(cols);
    int n = 0;
    for (int c = 0; c < cols; ++c) {
      float lr, w;
      if (ExposureSample(a, c * o.stride, r * o.stride, &lr, &w)) out[n++] = {lr, w};
    }
    made[std::size_t(r)] = n;
  }
  std::size_t kept = 0;
  for (int r = 0; r < rows; ++r)
    for (int i = 0; i < made[std::size_t(r)]; ++i)
      samples[kept++] = samples[std::size_t(r) * std::size_t(cols) + std::size_t(i)];
  samples.resize(kept);
  return WeightedMedianRatio(samples, o.min_samples);
}

ExposureEstimate WeightedMedianRatio(std::vector<std::pair<float, float>>& samples, int min_samples) {
  ExposureEstimate e;
  e.samples = long(samples.size());
  if (long(samples.size()) < min_samples) return e;
  // Sorted by (log ratio, weight), in two halves side by side: samples that compare equal
  // add the same weight, so the sums are those of any sorted order.
  par::Sort(par::Host{}, samples.begin(), samples.end());
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
