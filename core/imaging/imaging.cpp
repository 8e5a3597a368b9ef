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
  // Down-sample (mean of valid pixels), then integral images of count, sum and sum of squares.
  std::vector<double> cnt((sw + 1) * std::size_t(sh + 1), 0), s1(cnt.size(), 0), s2(cnt.size(), 0);
  auto at = [&](std::vector<double>& v, int x, int y) -> double& { return v[std::size_t(y) * (sw + 1) + x]; };
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) {
      double n = 0, a = 0, b = 0;
      for (int dy = 0; dy < f; ++dy)
        for (int dx = 0; dx < f; ++dx) {
          const int xx = x * f + dx, yy = y * f + dy;
          if (xx >= w || yy >= h) continue;
          const float v = lum(xx, yy);
          if (!(v > 0)) continue;
          n += 1;
          a += v;
        }
      const double mean = n > 0 ? a / n : 0;
      b = mean * mean;
      at(cnt, x + 1, y + 1) = (n > 0) + at(cnt, x, y + 1) + at(cnt, x + 1, y) - at(cnt, x, y);
      at(s1, x + 1, y + 1) = mean + at(s1, x, y + 1) + at(s1, x + 1, y) - at(s1, x, y);
      at(s2, x + 1, y + 1) = b + at(s2, x, y + 1) + at(s2, x + 1, y) - at(s2, x, y);
    }
  // Local statistics on the small grid.
  Image<float> mean_s(sw, sh), std_s(sw, sh);
  const int r = o.patch / 2;
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) {
      const int x0 = std::max(0, x - r), x1 = std::min(sw, x + r + 1);
      const int y0 = std::max(0, y - r), y1 = std::min(sh, y + r + 1);
      auto box = [&](std::vector<double>& v) {
        return at(v, x1, y1) - at(v, x0, y1) - at(v, x1, y0) + at(v, x0, y0);
      };
      const double n = box(cnt);
      if (n < 3) {
        mean_s(x, y) = 0;
        std_s(x, y) = 0;
        continue;
      }
      const double m = box(s1) / n;
      const double var = std::max(0.0, box(s2) / n - m * m);
      mean_s(x, y) = float(m);
      std_s(x, y) = float(std::sqrt(var));
    }
  // Up-sample bilinearly (pixel centres) and normalise.
  Image<float> out(w, h);
  if (mean_out) *mean_out = Image<float>(w, h);
  if (std_out) *std_out = Image<float>(w, h);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = lum(x, y);
      const float gx = std::clamp((x + 0.5f) / f - 0.5f, 0.f, float(sw - 1));
      const float gy = std::clamp((y + 0.5f) / f - 0.5f, 0.f, float(sh - 1));
      const int ix = std::min(int(gx), sw - 2 < 0 ? 0 : sw - 2), iy = std::min(int(gy), sh - 2 < 0 ? 0 : sh - 2);
      const float ax = sw > 1 ? gx - ix : 0, ay = sh > 1 ? gy - iy : 0;
      auto lerp2 = [&](const Image<float>& g) {
        const int ix1 = std::min(ix + 1, sw - 1), iy1 = std::min(iy + 1, sh - 1);
        return (1 - ay) * ((1 - ax) * g(ix, iy) + ax * g(ix1, iy)) +
               ay * ((1 - ax) * g(ix, iy1) + ax * g(ix1, iy1));
      };
      const float m = lerp2(mean_s), s = lerp2(std_s);
      if (mean_out) (*mean_out)(x, y) = m;
      if (std_out) (*std_out)(x, y) = s;
      out(x, y) = (v > 0 && m > 0) ? (v - m) / std::max(s, o.min_std * m) : 0.f;
    }
  return out;
}

Image<float> Downsample(const Image<float>& img) {
  Image<float> out(img.width() / 2, img.height() / 2);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x)
      out(x, y) = 0.25f * (img(2 * x, 2 * y) + img(2 * x + 1, 2 * y) + img(2 * x, 2 * y + 1) +
                           img(2 * x + 1, 2 * y + 1));
  return out;
}

DepthImage DownsampleDepth(const DepthImage& d) {
  DepthImage out(d.width() / 2, d.height() / 2);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      const float c = d(2 * x, 2 * y);
      if (!(c > 0)) {
        out(x, y) = 0;
        continue;
      }
      float sum = 0;
      int n = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const float v = d(2 * x + dx, 2 * y + dy);
          if (v > 0 && std::abs(v - c) < 0.05f * c) {
            sum += v;
            ++n;
          }
        }
      out(x, y) = sum / float(n);
    }
  return out;
}

DepthImage BilateralDepth(const DepthImage& d, float ss, float sd, int r) {
  DepthImage out(d.width(), d.height());
  // Spatial weights once; range weights from a table over |dz| in [0, 3 sigma] (beyond: 0).
  std::vector<float> spatial(std::size_t((2 * r + 1) * (2 * r + 1)));
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      spatial[std::size_t((dy + r) * (2 * r + 1) + dx + r)] = std::exp(-(dx * dx + dy * dy) / (2 * ss * ss));
  constexpr int kBins = 256;
  std::array<float, kBins + 1> range{};
  const float max_dz = 3 * sd, to_bin = kBins / max_dz;
  for (int i = 0; i <= kBins; ++i) {
    const float dz = float(i) / to_bin;
    range[std::size_t(i)] = i == kBins ? 0.f : std::exp(-dz * dz / (2 * sd * sd));
  }
#pragma omp parallel for schedule(static)
  for (int y = 0; y < d.height(); ++y)
    for (int x = 0; x < d.width(); ++x) {
      const float c = d(x, y);
      if (!(c > 0)) {
        out(x, y) = 0;
        continue;
      }
      float sw = 0, sv = 0;
      for (int dy = -r; dy <= r; ++dy) {
        const int yy = y + dy;
        if (yy < 0 || yy >= d.height()) continue;
        for (int dx = -r; dx <= r; ++dx) {
          const int xx = x + dx;
          if (xx < 0 || xx >= d.width()) continue;
          const float v = d(xx, yy);
          if (!(v > 0)) continue;
          const int bin = std::min(kBins, int(std::abs(v - c) * to_bin));
          const float wgt = spatial[std::size_t((dy + r) * (2 * r + 1) + dx + r)] * range[std::size_t(bin)];
          sw += wgt;
          sv += wgt * v;
        }
      }
      out(x, y) = sv / sw;
    }
  return out;
}

Image<Float3> VertexMap(const DepthImage& d, const PinholeCamera& cam) {
  Image<Float3> out(d.width(), d.height());
  for (int y = 0; y < d.height(); ++y)
    for (int x = 0; x < d.width(); ++x) {
      const float z = d(x, y);
      out(x, y) = z > 0 ? cam.BackProject(float(x), float(y), z) : Float3{0, 0, 0};
    }
  return out;
}

Image<Float3> NormalMap(const Image<Float3>& v, float max_jump) {
  Image<Float3> out(v.width(), v.height(), Float3{0, 0, 0});
  for (int y = 0; y + 1 < v.height(); ++y)
    for (int x = 0; x + 1 < v.width(); ++x) {
      const Float3 c = v(x, y), r = v(x + 1, y), b = v(x, y + 1);
      if (c.z <= 0 || r.z <= 0 || b.z <= 0) continue;
      if (std::abs(r.z - c.z) > max_jump * c.z || std::abs(b.z - c.z) > max_jump * c.z) continue;
      Float3 n = Cross(b - c, r - c);  // points towards the camera for a surface facing it
      const float len = Length(n);
      if (len <= 0) continue;
      n = n / len;
      if (Dot(n, c) > 0) n = -n;
      out(x, y) = n;
    }
  return out;
}

bool SampleBilinear(const Image<float>& img, float x, float y, float* out) {
  if (x < 0 || y < 0 || x > img.width() - 1.001f || y > img.height() - 1.001f) return false;
  const int ix = int(x), iy = int(y);
  const float ax = x - ix, ay = y - iy;
  *out = (1 - ay) * ((1 - ax) * img(ix, iy) + ax * img(ix + 1, iy)) +
         ay * ((1 - ax) * img(ix, iy + 1) + ax * img(ix + 1, iy + 1));
  return true;
}

}  // namespace hdrf::imaging
