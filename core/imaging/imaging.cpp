#include "imaging/imaging.h"

#include <algorithm>
#include <array>
#include <vector>
#include <cmath>

#include "common/error.h"
#include "imaging/imaging_impl.h"

namespace hdrf::imaging {

void ConvertFrame(const ColorImage& color, const radiometry::InverseResponse& inv,
                  const radiometry::PcfTables& pcf, int k, RadianceImage& radiance,
                  Image<float>& confidence, Image<float>& max_confidence, Device device) {
  if (k < 0 || k > 3) throw SettingError("pcf", "must be 0, 1, 2 or 3 (p0..p3)");
  const int w = color.width(), h = color.height();
  if (radiance.width() != w || radiance.height() != h) radiance = RadianceImage(w, h);
  if (confidence.width() != w || confidence.height() != h) confidence = Image<float>(w, h);
  if (max_confidence.width() != w || max_confidence.height() != h) max_confidence = Image<float>(w, h);
  const auto inverse = inv.Flat();
  std::array<float, 3 * 256> p{};
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) p[std::size_t(c * 256 + i)] = pcf[k][c][i];
  if (device == Device::kCuda) {
#if HDRF_HAS_CUDA
    detail::ConvertFrameCuda(color, inverse.data(), p.data(), radiance, confidence, max_confidence);
    return;
#else
    ThrowNoCudaBackend();
#endif
  }
  const long n = long(color.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i)
    ConvertPixel(color[std::size_t(i)], inverse.data(), p.data(), &radiance[std::size_t(i)],
                 &confidence[std::size_t(i)], &max_confidence[std::size_t(i)]);
}

Image<float> Luminance(const RadianceImage& r) {
  Image<float> out(r.width(), r.height());
  for (std::size_t i = 0; i < r.size(); ++i) out[i] = hdrf::Luminance(r[i]);
  return out;
}

Image<float> NormalizedRadiance(const Image<float>& lum, const NormalizedRadianceOptions& o,
                                Image<float>* mean_out, Image<float>* std_out) {
  if (o.patch < 3 || o.patch % 2 == 0) throw SettingError("nr.patch", "must be odd and >= 3");
  if (o.downsample < 1) throw SettingError("nr.downsample", "must be >= 1");
  const int w = lum.width(), h = lum.height(), f = o.downsample;
  const int sw = (w + f - 1) / f, sh = (h + f - 1) / f;
  // Down-sample (mean of valid pixels), integral images, local statistics on the small grid.
  Image<float> cells(sw, sh);
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) cells(x, y) = NrCellMean(View(lum), x, y, f);
  Image<double> cnt(sw + 1, sh + 1), s1(sw + 1, sh + 1), s2(sw + 1, sh + 1);
  const NrIntegrals in{View(cnt), View(s1), View(s2)};
  for (int y = 0; y < sh; ++y) NrRowPass(View(cells), in, y);
  for (int x = 0; x <= sw; ++x) NrColumnPass(in, x);
  Image<float> mean_s(sw, sh), std_s(sw, sh);
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) NrLocalStats(in, x, y, o.patch / 2, &mean_s(x, y), &std_s(x, y));
  // Up-sample bilinearly (pixel centres) and normalise.
  Image<float> out(w, h);
  if (mean_out) *mean_out = Image<float>(w, h);
  if (std_out) *std_out = Image<float>(w, h);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      NrPixel(View(lum), View(mean_s), View(std_s), f, o.min_std, x, y, &out(x, y),
              mean_out ? &(*mean_out)(x, y) : nullptr, std_out ? &(*std_out)(x, y) : nullptr);
  return out;
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
  const BilateralTables t = MakeBilateralTables(ss, sd, r);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < d.height(); ++y)
    for (int x = 0; x < d.width(); ++x) out(x, y) = BilateralPixel(View(d), t, x, y);
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
