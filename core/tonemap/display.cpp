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
}  // namespace

float LogAverageLuminance(const Float3* rgb, std::size_t n) {
  double s = 0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float l = Luminance(rgb[i]);
    if (l > 0 && std::isfinite(l)) {
      s += std::log(double(l));
      ++k;
    }
  }
  return k ? float(std::exp(s / double(k))) : 1.f;
}

ColorImage Reinhard(const RadianceImage& radiance, float key) {
  const float scale = key / LogAverageLuminance(radiance.data(), radiance.size());
  ColorImage out(radiance.width(), radiance.height());
  for (std::size_t i = 0; i < radiance.size(); ++i) {
    const Float3 d = ReinhardPixel(radiance[i] * scale);
    out[i] = {To8(d.x), To8(d.y), To8(d.z)};
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
