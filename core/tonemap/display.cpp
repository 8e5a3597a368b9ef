#include "tonemap/display.h"

#include <algorithm>
#include <cmath>

namespace hdrf::tonemap {

float SrgbEncode(float v) {
  v = std::clamp(v, 0.f, 1.f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

namespace {
std::uint8_t To8(float v) { return std::uint8_t(std::lround(SrgbEncode(v) * 255.f)); }
bool Usable(Float3 c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && Luminance(c) > 0;
}
}  // namespace

ColorImage Reinhard(const RadianceImage& radiance, float key) {
  double log_sum = 0;
  long n = 0;
  for (std::size_t i = 0; i < radiance.size(); ++i)
    if (Usable(radiance[i])) {
      log_sum += std::log(1e-6 + Luminance(radiance[i]));
      ++n;
    }
  const float log_avg = n ? float(std::exp(log_sum / double(n))) : 1.f;
  const float scale = key / log_avg;
  ColorImage out(radiance.width(), radiance.height());
  for (std::size_t i = 0; i < radiance.size(); ++i) {
    const Float3 c = radiance[i];
    if (!Usable(c)) {
      out[i] = {0, 0, 0};
      continue;
    }
    const float l = Luminance(c) * scale;
    const float ratio = (l / (1.f + l)) / Luminance(c);
    out[i] = {To8(std::max(0.f, c.x) * ratio), To8(std::max(0.f, c.y) * ratio),
              To8(std::max(0.f, c.z) * ratio)};
  }
  return out;
}

ColorImage ColorizeDepth(const DepthImage& depth_m, float min_m, float max_m) {
  // A monotone-luminance ramp: dark blue -> purple -> orange -> yellow.
  static const Float3 kStops[5] = {
      {0.99f, 0.91f, 0.15f}, {0.96f, 0.52f, 0.18f}, {0.75f, 0.22f, 0.42f},
      {0.36f, 0.09f, 0.55f}, {0.08f, 0.05f, 0.30f}};
  ColorImage out(depth_m.width(), depth_m.height());
  const float span = std::max(1e-6f, max_m - min_m);
  for (std::size_t i = 0; i < depth_m.size(); ++i) {
    const float d = depth_m[i];
    if (!(d > 0)) {
      out[i] = {0, 0, 0};
      continue;
    }
    const float t = std::clamp((d - min_m) / span, 0.f, 1.f) * 4.f;
    const int k = std::min(3, int(t));
    const Float3 c = kStops[k] + (kStops[k + 1] - kStops[k]) * (t - float(k));
    out[i] = {std::uint8_t(c.x * 255.f), std::uint8_t(c.y * 255.f), std::uint8_t(c.z * 255.f)};
  }
  return out;
}

}  // namespace hdrf::tonemap
