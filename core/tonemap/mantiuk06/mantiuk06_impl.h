// Per-element steps of the contrast-domain operator (Mantiuk, Myszkowski, Seidel 2006),
// shared by the CPU loops (mantiuk06.cpp) and the CUDA kernels (mantiuk06_cuda.cu).
//
// Log luminance is described by its gradients on every level of a pyramid (each level half
// the size of the one before, by area averaging). The gradients are taken to a perceptual
// response, compressed there (scaled: contrast mapping; or equalised), taken back, and the
// log luminance whose pyramid gradients best match them, weighted by how visible a change of
// each is, is solved for by conjugate gradients.
#pragma once

#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"

namespace hdrf::tonemap::m06 {

// Area-average downsampling by 2 (the output is floor(w / 2) x floor(h / 2); with an odd
// size each output pixel covers a fractional footprint of the input).
HDRF_HD int MinInt(int a, int b) { return a < b ? a : b; }

HDRF_HD float Overlap(int out, float scale, int in) {
  const float a = fmaxf(float(out) * scale, float(in)), b = fminf(float(out + 1) * scale, float(in + 1));
  return fmaxf(b - a, 0.f);
}

HDRF_HD float Downsample(ImageView<const float> in, int ow, int oh, int x, int y) {
  const float sx = float(in.width) / float(ow), sy = float(in.height) / float(oh);
  const int x0 = int(float(x) * sx), x1 = MinInt(int(ceilf(float(x + 1) * sx)), in.width);
  const int y0 = int(float(y) * sy), y1 = MinInt(int(ceilf(float(y + 1) * sy)), in.height);
  float s = 0;
  for (int j = y0; j < y1; ++j) {
    const float wy = Overlap(y, sy, j);
    for (int i = x0; i < x1; ++i) s += wy * Overlap(x, sx, i) * in(i, j);
  }
  return s / (sx * sy);
}

// The adjoint of Downsample scaled by the area ratio: each fine pixel gathers the coarse
// pixels whose footprint covers it, weighted by the overlap (for even sizes, replication).
// Using the adjoint keeps the solved system symmetric.
HDRF_HD float Upsample(ImageView<const float> coarse, int fw, int fh, int x, int y) {
  const float sx = float(fw) / float(coarse.width), sy = float(fh) / float(coarse.height);
  const int cx0 = int(float(x) / sx), cx1 = MinInt(int(float(x + 1) / sx), coarse.width - 1);
  const int cy0 = int(float(y) / sy), cy1 = MinInt(int(float(y + 1) / sy), coarse.height - 1);
  float s = 0;
  for (int cy = cy0; cy <= cy1 && cy < coarse.height; ++cy) {
    const float wy = Overlap(cy, sy, y);
    for (int cx = cx0; cx <= cx1 && cx < coarse.width; ++cx) s += wy * Overlap(cx, sx, x) * coarse(cx, cy);
  }
  return s;
}

// Forward differences; zero across the last column (x) and the last row (y).
HDRF_HD float GradX(ImageView<const float> l, int x, int y) { return x + 1 < l.width ? l(x + 1, y) - l(x, y) : 0.f; }
HDRF_HD float GradY(ImageView<const float> l, int x, int y) { return y + 1 < l.height ? l(x, y + 1) - l(x, y) : 0.f; }

// Divergence (the negative adjoint of the gradient above).
HDRF_HD float Divergence(ImageView<const float> gx, ImageView<const float> gy, int x, int y) {
  return gx(x, y) - (x > 0 ? gx(x - 1, y) : 0.f) + gy(x, y) - (y > 0 ? gy(x, y - 1) : 0.f);
}

// Weight of a gradient in the fit: the inverse of the contrast discrimination threshold at
// that contrast (a change of a large contrast is less visible), from the threshold model
// dG(G) = 0.038737 G^0.537756 (G in log10 units, at least 0.001).
HDRF_HD float FitWeight(float g) {
  const float a = fmaxf(fabsf(g), 0.001f);
  return 1.f / (0.038737f * powf(a, 0.537756f));
}

// The transducer as a table: response at G = i * kTableStep (log10 contrast), i in
// [0, kTableSize); odd (R(-G) = -R(G)); and its inverse on a response grid.
constexpr int kTableSize = 1024;
constexpr float kTableStep = 6.f / float(kTableSize - 1);  // G up to 6 log10 units

struct Transducer {
  float response[kTableSize];      // R(i * kTableStep)
  float inverse[kTableSize];       // G(j * inverse_step)
  float inverse_step;
};

HDRF_HD float ToResponse(const Transducer& t, float g) {
  const float f = fabsf(g) / kTableStep;
  float r;
  if (f >= float(kTableSize - 1)) {
    r = t.response[kTableSize - 1] + (f - float(kTableSize - 1)) * (t.response[kTableSize - 1] - t.response[kTableSize - 2]);
  } else {
    const int i = int(f);
    r = t.response[i] + (t.response[i + 1] - t.response[i]) * (f - float(i));
  }
  return g < 0 ? -r : r;
}

HDRF_HD float ToContrast(const Transducer& t, float r) {
  const float f = fabsf(r) / t.inverse_step;
  float g;
  if (f >= float(kTableSize - 1)) {
    g = t.inverse[kTableSize - 1] + (f - float(kTableSize - 1)) * (t.inverse[kTableSize - 1] - t.inverse[kTableSize - 2]);
  } else {
    const int i = int(f);
    g = t.inverse[i] + (t.inverse[i + 1] - t.inverse[i]) * (f - float(i));
  }
  return r < 0 ? -g : g;
}

// Equalisation: a response gradient (rx, ry) rescaled so that its magnitude becomes
// `factor` times the fraction of all magnitudes below it (cdf over [0, top] in `bins`).
HDRF_HD float EqualiseScale(float rx, float ry, const float* cdf, int bins, float top, float factor) {
  const float m = sqrtf(rx * rx + ry * ry);
  if (!(m > 0) || !(top > 0)) return 0.f;
  const float fb = m * float(bins) / top;
  const int b = MinInt(bins - 1, int(fb));
  const float c = cdf[b] + (cdf[b + 1] - cdf[b]) * (fb - float(b));
  return factor * c / m;
}

// The display mapping of the solved log luminance x: [lo, hi] onto the top 2.3 log10 units,
// colour ratios raised to the saturation; display-linear, clamped to [0, 1].
constexpr float kDisplayRange = 2.3f;
// The display range a result spans: its 0.1 % to 99.9 % range (lo, lo + span) mapped onto
// the display's kDisplayRange log10 units. A result flatter than kFlatResult (a uniform
// image: what is left is the solver's rounding) is shown as one mid grey, not its rounding
// stretched into stripes.
inline constexpr float kFlatResult = 1e-3f;
HDRF_HD void DisplaySpan(float l_lo, float l_hi, float* lo, float* span) {
  if (l_hi - l_lo < kFlatResult) {
    *span = kDisplayRange;
    *lo = 0.5f * (l_lo + l_hi) - 0.5f * kDisplayRange;
  } else {
    *lo = l_lo;
    *span = l_hi - l_lo;
  }
}

HDRF_HD Float3 DisplayPixel(Float3 c, float x, float lo, float span, float clip, float sat) {
  const float y = powf(10.f, (x - lo) / span * kDisplayRange - kDisplayRange);
  const float lum = fmaxf(Luminance(c), clip);
  const float v[3] = {c.x, c.y, c.z};
  float d[3];
  for (int k = 0; k < 3; ++k) d[k] = fminf(fmaxf(powf(fmaxf(v[k], clip) / lum, sat) * y, 0.f), 1.f);
  return {d[0], d[1], d[2]};
}

}  // namespace hdrf::tonemap::m06
