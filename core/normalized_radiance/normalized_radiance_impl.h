// Per-pixel steps of normalized radiance (the paper's step 3), shared by the CPU and CUDA
// drivers (normalized_radiance_driver.h): cell means of a down-sampled luminance, integral
// images of their count, sum and sum of squares, local statistics over the patch, and the
// bilinear up-sampling with the normalization itself.
#pragma once

#include "common/host_device.h"
#include "common/image_view.h"

namespace hdrf::nr {

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
// Both passes read a few entries ahead of their sums (kNrAhead at a time): the reads do not
// wait on the stores before them, while the sums run in the same order (the same bits).
// These are the CPU's passes (and the GPU's row pass for rows too wide for shared memory);
// the GPU runs the same additions in its own kernels (normalized_radiance_cuda.cu: one
// thread per column and per sum, three threads in step per row).
inline constexpr int kNrAhead = 8;
HDRF_HD void NrRowPass(ImageView<const float> cells, NrIntegrals in, int y) {
  double c = 0, a = 0, b = 0;
  in.cnt(0, y + 1) = 0;
  in.s1(0, y + 1) = 0;
  in.s2(0, y + 1) = 0;
  for (int x0 = 0; x0 < cells.width; x0 += kNrAhead) {
    float m[kNrAhead];
    HDRF_UNROLL
    for (int k = 0; k < kNrAhead; ++k) m[k] = x0 + k < cells.width ? cells(x0 + k, y) : 0.f;
    HDRF_UNROLL
    for (int k = 0; k < kNrAhead; ++k) {
      if (x0 + k >= cells.width) break;
      const double v = m[k];
      const double v2 = v * v;
      c += v > 0 ? 1.0 : 0.0;
      a += v;
      b += v2;
      in.cnt(x0 + k + 1, y + 1) = c;
      in.s1(x0 + k + 1, y + 1) = a;
      in.s2(x0 + k + 1, y + 1) = b;
    }
  }
}
HDRF_HD void NrColumnPass(NrIntegrals in, int x) {
  in.cnt(x, 0) = 0;
  in.s1(x, 0) = 0;
  in.s2(x, 0) = 0;
  double c = 0, a = 0, b = 0;
  const int h = in.cnt.height;
  for (int y0 = 1; y0 < h; y0 += kNrAhead) {
    double dc[kNrAhead], da[kNrAhead], db[kNrAhead];
    HDRF_UNROLL
    for (int k = 0; k < kNrAhead; ++k) {
      const bool in_range = y0 + k < h;
      dc[k] = in_range ? in.cnt(x, y0 + k) : 0.0;
      da[k] = in_range ? in.s1(x, y0 + k) : 0.0;
      db[k] = in_range ? in.s2(x, y0 + k) : 0.0;
    }
    HDRF_UNROLL
    for (int k = 0; k < kNrAhead; ++k) {
      if (y0 + k >= h) break;
      c += dc[k];
      a += da[k];
      b += db[k];
      in.cnt(x, y0 + k) = c;
      in.s1(x, y0 + k) = a;
      in.s2(x, y0 + k) = b;
    }
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

}  // namespace hdrf::nr
