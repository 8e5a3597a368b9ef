#include "imaging/imaging.h"

#include <algorithm>
#include <array>
#include <vector>
#include <cmath>

#include "common/error.h"
#include "imaging/imaging_driver.h"
#include "imaging/imaging_impl.h"

namespace hdrf::imaging {

void DepthFilterOptions::Check() const {
  if (!(sigma_space_px > 0) || !std::isfinite(sigma_space_px))
    throw SettingError("depth.sigma_space_px", "must be a positive number of pixels");
  if (!(sigma_depth_m > 0) || !std::isfinite(sigma_depth_m))
    throw SettingError("depth.sigma_depth_m", "must be a positive number of metres");
  if (radius < 1 || radius > kBilateralMaxRadius)
    throw SettingError("depth.radius", "must be 1 to " + std::to_string(kBilateralMaxRadius) + " pixels");
  if (!(max_normal_jump_m > 0) || !std::isfinite(max_normal_jump_m))
    throw SettingError("depth.max_normal_jump_m", "must be a positive number of metres");
}

Image<float> Downsample(const Image<float>& img) {
  Image<float> out(img.width() / 2, img.height() / 2);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) out(x, y) = Mean2x2(View(img), x, y);
  return out;
}

DepthImage DownsampleDepth(const DepthImage& d) {
  DepthImage out(d.width() / 2, d.height() / 2);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) out(x, y) = DownsampleDepthPixel(View(d), x, y);
  return out;
}

BilateralTables MakeBilateralTables(float ss, float sd, int r) {
  if (r < 1 || r > kBilateralMaxRadius)
    throw SettingError("bilateral radius", "must be 1.." + std::to_string(kBilateralMaxRadius));
  if (!(ss > 0) || !(sd > 0)) throw SettingError("bilateral sigma", "must be > 0");
  // Spatial weights once; range weights from a table over |dz| in [0, 3 sigma] (beyond: 0).
  BilateralTables t{};
  t.radius = r;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      t.spatial[(dy + r) * (2 * r + 1) + dx + r] = std::exp(-(dx * dx + dy * dy) / (2 * ss * ss));
  const float max_dz = 3 * sd;
  t.to_bin = kBilateralBins / max_dz;
  for (int i = 0; i <= kBilateralBins; ++i) {
    const float dz = float(i) / t.to_bin;
    t.range[i] = i == kBilateralBins ? 0.f : std::exp(-dz * dz / (2 * sd * sd));
  }
  return t;
}

DepthImage BilateralDepth(const DepthImage& d, float ss, float sd, int r) {
  DepthImage out(d.width(), d.height());
  BilateralFilter(par::Host{}, View(d), MakeBilateralTables(ss, sd, r), View(out));
  return out;
}

Image<Float3> VertexMap(const DepthImage& d, const PinholeCamera& cam) {
  Image<Float3> out(d.width(), d.height());
  for (int y = 0; y < d.height(); ++y)
    for (int x = 0; x < d.width(); ++x) out(x, y) = VertexPixel(View(d), cam, x, y);
  return out;
}

Image<Float3> NormalMap(const Image<Float3>& v, float max_jump) {
  Image<Float3> out(v.width(), v.height());
  for (int y = 0; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x) out(x, y) = NormalPixel(View(v), max_jump, x, y);
  return out;
}

bool SampleBilinear(const Image<float>& img, float x, float y, float* out) {
  return SampleBilinear(View(img), x, y, out);
}

}  // namespace hdrf::imaging
