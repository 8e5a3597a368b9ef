// Per-pixel steps of imaging, shared by the CPU loops (imaging.cpp) and the CUDA kernels
// (imaging_cuda.cu). Both backends call exactly these functions, so they agree to the bit
// wherever the arithmetic is plain IEEE (the CUDA build is compiled without FMA contraction).
#pragma once

#include "common/camera.h"
#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"

namespace hdrf::imaging {

// Radiance f^-1(I) and confidence of one pixel: `inverse` and `pcf` are channel-major
// 3 x 256 tables (the chosen PCF variant); levels 0 and 255 carry no confidence.
HDRF_HD void ConvertPixel(Rgb8 c, const float* inverse, const float* pcf, Float3* radiance,
                          float* confidence, float* max_confidence) {
  *radiance = {inverse[c.r], inverse[256 + c.g], inverse[512 + c.b]};
  const int lv[3] = {c.r, c.g, c.b};
  float sum = 0.f, mx = 0.f;
  for (int ch = 0; ch < 3; ++ch) {
    const float q = (lv[ch] == 0 || lv[ch] == 255) ? 0.f : pcf[ch * 256 + lv[ch]];
    sum += q;
    mx = q > mx ? q : mx;
  }
  *confidence = sum / 3.f;
  *max_confidence = mx;
}

// ---- Normalized radiance ------------------------------------------------------------------
// 1. Mean of the valid (> 0) pixels of the f x f cell (x, y) of the luminance; 0 if none.
HDRF_HD float NrCellMean(ImageView<const float> lum, int x, int y, int f) {
  float a = 0.f;
  int n = 0;
  for (int dy = 0; dy < f; ++dy)
    for (int dx = 0; dx < f; ++dx) {
      const int xx = x * f + dx, yy = y * f + dy;
      if (xx >= lum.width || yy >= lum.height) continue;
      const float v = lum(xx, yy);
      if (!(v > 0.f)) continue;
      ++n;
      a += v;
    }
  return n > 0 ? a / float(n) : 0.f;
}

// 2. Integral images of (count, sum, sum of squares) of the cell means, (sw+1) x (sh+1),
// built as a running sum along each row (RowPass) and then down each column (ColumnPass),
// in double. Entry 0 of each row and column is 0.
struct NrIntegrals {
  ImageView<double> cnt, s1, s2;
};
HDRF_HD void NrRowPass(ImageView<const float> cells, NrIntegrals in, int y) {
  double c = 0, a = 0, b = 0;
  in.cnt(0, y + 1) = 0;
  in.s1(0, y + 1) = 0;
  in.s2(0, y + 1) = 0;
  for (int x = 0; x < cells.width; ++x) {
    const double m = cells(x, y);
    const double m2 = m * m;
    c += m > 0 ? 1.0 : 0.0;
    a += m;
    b += m2;
    in.cnt(x + 1, y + 1) = c;
    in.s1(x + 1, y + 1) = a;
    in.s2(x + 1, y + 1) = b;
  }
}
HDRF_HD void NrColumnPass(NrIntegrals in, int x) {
  in.cnt(x, 0) = 0;
  in.s1(x, 0) = 0;
  in.s2(x, 0) = 0;
  double c = 0, a = 0, b = 0;
  for (int y = 1; y < in.cnt.height; ++y) {
    c += in.cnt(x, y);
    a += in.s1(x, y);
    b += in.s2(x, y);
    in.cnt(x, y) = c;
    in.s1(x, y) = a;
    in.s2(x, y) = b;
  }
}
// 3. Local mean and std over the patch (radius r cells) around cell (x, y); 0 where fewer
// than 3 cells have data.
HDRF_HD void NrLocalStats(NrIntegrals in, int x, int y, int r, float* mean, float* stddev) {
  const int sw = in.cnt.width - 1, sh = in.cnt.height - 1;
  const int x0 = x - r < 0 ? 0 : x - r, x1 = x + r + 1 > sw ? sw : x + r + 1;
  const int y0 = y - r < 0 ? 0 : y - r, y1 = y + r + 1 > sh ? sh : y + r + 1;
  const double n = in.cnt(x1, y1) - in.cnt(x0, y1) - in.cnt(x1, y0) + in.cnt(x0, y0);
  if (n < 3) {
    *mean = 0.f;
    *stddev = 0.f;
    return;
  }
  const double m = (in.s1(x1, y1) - in.s1(x0, y1) - in.s1(x1, y0) + in.s1(x0, y0)) / n;
  const double e2 = (in.s2(x1, y1) - in.s2(x0, y1) - in.s2(x1, y0) + in.s2(x0, y0)) / n;
  const double m2 = m * m;
  const double var = e2 - m2 > 0 ? e2 - m2 : 0.0;
  *mean = float(m);
  *stddev = float(sqrt(var));
}
// 4. Bilinear up-sampling of the cell statistics to pixel (x, y) (pixel centres), and the
// normalized value (v - mean) / max(std, min_std * mean); 0 where there is no data.
HDRF_HD void NrPixel(ImageView<const float> lum, ImageView<const float> mean_s,
                     ImageView<const float> std_s, int f, float min_std, int x, int y, float* nr,
                     float* mean_out, float* std_out) {
  const int sw = mean_s.width, sh = mean_s.height;
  const float v = lum(x, y);
  float gx = (x + 0.5f) / float(f) - 0.5f, gy = (y + 0.5f) / float(f) - 0.5f;
  gx = gx < 0.f ? 0.f : (gx > float(sw - 1) ? float(sw - 1) : gx);
  gy = gy < 0.f ? 0.f : (gy > float(sh - 1) ? float(sh - 1) : gy);
  const int lx = sw - 2 < 0 ? 0 : sw - 2, ly = sh - 2 < 0 ? 0 : sh - 2;
  const int ix = int(gx) < lx ? int(gx) : lx, iy = int(gy) < ly ? int(gy) : ly;
  const float ax = sw > 1 ? gx - float(ix) : 0.f, ay = sh > 1 ? gy - float(iy) : 0.f;
  const int ix1 = ix + 1 < sw ? ix + 1 : sw - 1, iy1 = iy + 1 < sh ? iy + 1 : sh - 1;
  const float m = (1 - ay) * ((1 - ax) * mean_s(ix, iy) + ax * mean_s(ix1, iy)) +
                  ay * ((1 - ax) * mean_s(ix, iy1) + ax * mean_s(ix1, iy1));
  const float s = (1 - ay) * ((1 - ax) * std_s(ix, iy) + ax * std_s(ix1, iy)) +
                  ay * ((1 - ax) * std_s(ix, iy1) + ax * std_s(ix1, iy1));
  if (mean_out) *mean_out = m;
  if (std_out) *std_out = s;
  const float floor_s = min_std * m;
  *nr = (v > 0.f && m > 0.f) ? (v - m) / (s > floor_s ? s : floor_s) : 0.f;
}

// ---- Pyramids -------------------------------------------------------------------------------
HDRF_HD float Mean2x2(ImageView<const float> in, int x, int y) {
  return 0.25f * (in(2 * x, 2 * y) + in(2 * x + 1, 2 * y) + in(2 * x, 2 * y + 1) + in(2 * x + 1, 2 * y + 1));
}
// Mean of the valid neighbours within 5 % of the top-left sample's depth (0 stays 0).
HDRF_HD float DownsampleDepthPixel(ImageView<const float> d, int x, int y) {
  const float c = d(2 * x, 2 * y);
  if (!(c > 0.f)) return 0.f;
  float sum = 0.f;
  int n = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const float v = d(2 * x + dx, 2 * y + dy);
      if (v > 0.f && fabsf(v - c) < 0.05f * c) {
        sum += v;
        ++n;
      }
    }
  return sum / float(n);
}

// ---- Bilateral depth filter ---------------------------------------------------------------
inline constexpr int kBilateralMaxRadius = 5;
inline constexpr int kBilateralBins = 256;
struct BilateralTables {
  int radius = 3;
  float to_bin = 0;  // range-table bins per metre of |dz|
  float spatial[(2 * kBilateralMaxRadius + 1) * (2 * kBilateralMaxRadius + 1)];
  float range[kBilateralBins + 1];  // last bin: beyond 3 sigma, weight 0
};
HDRF_HD float BilateralPixel(ImageView<const float> d, const BilateralTables& t, int x, int y) {
  const float c = d(x, y);
  if (!(c > 0.f)) return 0.f;
  const int r = t.radius, side = 2 * r + 1;
  float sw = 0.f, sv = 0.f;
  for (int dy = -r; dy <= r; ++dy) {
    const int yy = y + dy;
    if (yy < 0 || yy >= d.height) continue;
    for (int dx = -r; dx <= r; ++dx) {
      const int xx = x + dx;
      if (xx < 0 || xx >= d.width) continue;
      const float v = d(xx, yy);
      if (!(v > 0.f)) continue;
      int bin = int(fabsf(v - c) * t.to_bin);
      bin = bin < kBilateralBins ? bin : kBilateralBins;
      const float wgt = t.spatial[(dy + r) * side + dx + r] * t.range[bin];
      sw += wgt;
      sv += wgt * v;
    }
  }
  return sv / sw;
}

// ---- Vertex and normal maps ---------------------------------------------------------------
HDRF_HD Float3 VertexPixel(ImageView<const float> d, const PinholeCamera& cam, int x, int y) {
  const float z = d(x, y);
  return z > 0.f ? cam.BackProject(float(x), float(y), z) : Float3{0, 0, 0};
}
// Normal from the right and lower neighbours, facing the camera; zero where undefined.
HDRF_HD Float3 NormalPixel(ImageView<const Float3> v, float max_jump, int x, int y) {
  const Float3 zero{0, 0, 0};
  if (x + 1 >= v.width || y + 1 >= v.height) return zero;
  const Float3 c = v(x, y), r = v(x + 1, y), b = v(x, y + 1);
  if (c.z <= 0.f || r.z <= 0.f || b.z <= 0.f) return zero;
  if (fabsf(r.z - c.z) > max_jump * c.z || fabsf(b.z - c.z) > max_jump * c.z) return zero;
  Float3 n = Cross(b - c, r - c);
  const float len = Length(n);
  if (len <= 0.f) return zero;
  n = n / len;
  if (Dot(n, c) > 0.f) n = -n;
  return n;
}

// Central differences (0 on the border).
HDRF_HD float GradXPixel(ImageView<const float> im, int x, int y) {
  return (x > 0 && x + 1 < im.width) ? 0.5f * (im(x + 1, y) - im(x - 1, y)) : 0.f;
}
HDRF_HD float GradYPixel(ImageView<const float> im, int x, int y) {
  return (y > 0 && y + 1 < im.height) ? 0.5f * (im(x, y + 1) - im(x, y - 1)) : 0.f;
}

// Bilinear sample; false when a needed neighbour is outside.
HDRF_HD bool SampleBilinear(ImageView<const float> img, float x, float y, float* out) {
  if (x < 0.f || y < 0.f || x > float(img.width) - 1.001f || y > float(img.height) - 1.001f) return false;
  const int ix = int(x), iy = int(y);
  const float ax = x - float(ix), ay = y - float(iy);
  *out = (1 - ay) * ((1 - ax) * img(ix, iy) + ax * img(ix + 1, iy)) +
         ay * ((1 - ax) * img(ix, iy + 1) + ax * img(ix + 1, iy + 1));
  return true;
}

// Grey level in [0, 1] of the delivered colour: the brightness-constancy baseline's input.
HDRF_HD float RawIntensityPixel(Rgb8 c) { return float(c.r + c.g + c.b) / 765.f; }

}  // namespace hdrf::imaging
