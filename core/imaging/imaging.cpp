#include "imaging/imaging.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>
#include <cmath>

#include "common/error.h"
#include "common/lanes.h"
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

namespace {

// BilateralPixel for pixels x .. x + 3 of row y, whose windows lie inside the image: each
// lane adds its pixel's taps in the same order with the same operations. A tap that
// BilateralPixel skips (no depth) adds +0 to sums that are +0 or more: no bit changes.
void BilateralFour(ImageView<const float> d, const BilateralTables& t, int x, int y, float* out) {
  const int r = t.radius, side = 2 * r + 1;
  Lanes c;
  std::memcpy(&c, &d(x, y), sizeof c);
  const Lanes zero = {0.f, 0.f, 0.f, 0.f}, top = zero + float(kBilateralBins), huge = zero + 3.0e38f;
  const Lanes to_bin = zero + t.to_bin;
  const LaneInts sign = {0x7fffffff, 0x7fffffff, 0x7fffffff, 0x7fffffff};
  Lanes sw = zero, sv = zero;
  for (int dy = -r; dy <= r; ++dy) {
    const float* row = &d(x - r, y + dy);
    const int k0 = (dy + r) * side;
    for (int i = 0; i < side; ++i) {
      Lanes v;
      std::memcpy(&v, row + i, sizeof v);
      const LaneInts valid = (v > zero) & (v <= huge);
      const Lanes fb = (Lanes)((LaneInts)(v - c) & sign) * to_bin;  // |v - c| * to_bin
      // fb < bins ? int(fb) : bins, where a tap without depth (fb may be NaN) takes the last bin.
      const LaneInts bin = __builtin_convertvector(valid ? (fb < top ? fb : top) : top, LaneInts);
      const float spatial = t.spatial[k0 + i];
      const Lanes range = {t.range[bin[0]], t.range[bin[1]], t.range[bin[2]], t.range[bin[3]]};
      const Lanes wgt = valid ? spatial * range : zero;
      sw += wgt;
      sv += valid ? wgt * v : zero;
    }
  }
  for (int k = 0; k < 4; ++k) out[k] = c[k] > 0.f && c[k] <= 3.0e38f ? sv[k] / sw[k] : 0.f;
}

}  // namespace

void BilateralFilter(par::Host, ImageView<const float> depth_m, const BilateralTables& t, ImageView<float> out) {
  const int w = depth_m.width, h = depth_m.height, r = t.radius;
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < h; ++y) {
    int x = 0;
    if (y >= r && y + r < h) {
      for (; x < r; ++x) out(x, y) = BilateralPixel(depth_m, t, x, y);
      for (; x + 3 + r < w; x += 4) BilateralFour(depth_m, t, x, y, &out(x, y));
    }
    for (; x < w; ++x) out(x, y) = BilateralPixel(depth_m, t, x, y);
  }
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
