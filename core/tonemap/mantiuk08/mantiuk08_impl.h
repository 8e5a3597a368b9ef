// Per-element steps of the display-adaptive operator (Mantiuk, Daly, Kerofsky 2008), shared
// by the CPU loops (mantiuk08.cpp) and the CUDA kernels (mantiuk08_cuda.cu).
//
// The image is analysed on log10 luminance: a stack of band-pass images (differences of
// successive a-trous low-pass images) gives, per band, a histogram of (background log
// luminance, band contrast) pairs -- the conditional density the tone curve is optimised
// for. The curve is then applied per pixel as a lookup table with a colour correction that
// follows the local slope of the curve.
#pragma once

#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"

namespace hdrf::tonemap::m08 {

// Curve nodes: log10 luminance from kLogMin to kLogMax in kStep.
constexpr float kLogMin = -8.f;
constexpr float kLogMax = 8.f;
constexpr float kStep = 0.1f;
constexpr int kNodes = 161;
// Band contrasts are binned from -kContrastMax to +kContrastMax in kStep: 15 bins, the
// middle one (no contrast) at kZeroBin.
constexpr float kContrastMax = 0.7f;
constexpr int kContrastBins = 15;
constexpr int kZeroBin = kContrastBins / 2;
// Contrasts between this and half a bin are counted in the first bin beside zero rather
// than as no contrast (a contrast just above the visibility threshold must constrain the
// curve), in log10 units.
constexpr float kVisibleContrast = 0.0043f;
constexpr int kMaxBands = 9;
// Luminance is clamped to [floor, kMaxLum] before the log (floor: the smallest positive
// luminance of the image, at least kMinLum).
constexpr float kMinLum = 1e-8f;
constexpr float kMaxLum = 1e8f;

HDRF_HD float ClampedLog10(float lum, float floor) {
  return log10f(fminf(fmaxf(lum, floor), kMaxLum));
}

HDRF_HD int Mirror(int i, int n) {
  if (i < 0) i = -i;
  if (i >= n) i = 2 * n - 2 - i;
  return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

// One pass of the separable 5-tap low-pass, taps `step` pixels apart, along x or y.
HDRF_HD float LowPassTap(ImageView<const float> in, int x, int y, int step, bool along_x) {
  constexpr float kA = 0.4f;
  const float w[5] = {0.25f - kA / 2, 0.25f, kA, 0.25f, 0.25f - kA / 2};
  float s = 0;
  for (int j = 0; j < 5; ++j) {
    const int o = (j - 2) * step;
    s += w[j] * (along_x ? in(Mirror(x + o, in.width), y) : in(x, Mirror(y + o, in.height)));
  }
  return s;
}

// Histogram cell of one pixel: background (low-pass) node and contrast bin, or -1 where the
// background is out of the node range or the contrast beyond kContrastMax.
HDRF_HD int DensityCell(float high, float low) {
  const float g = high - low;
  const int node = int((low - kLogMin) / kStep + 0.5f);
  if (node < 0 || node >= kNodes) return -1;
  int bin = int((g + kContrastMax) / kStep + 0.5f);  // truncates: half a bin below the range counts in bin 0
  if (bin < 0 || bin >= kContrastBins) return -1;
  if (g > kVisibleContrast && g < kStep / 2)
    bin = kZeroBin + 1;
  else if (g < -kVisibleContrast && g > -kStep / 2)
    bin = kZeroBin - 1;
  return node * kContrastBins + bin;
}

// The curve as lookup tables over the nodes: display luminance (cd/m^2) and the colour
// correction exponent; and the display's offset and range for display-linear output.
struct CurveLut {
  float lum[kNodes];
  float sat[kNodes];
  float floor;          // luminance floor of the image (see ClampedLog10)
  float offset, range;  // display: black + reflected ambient, peak - black (cd/m^2)
};

HDRF_HD float Interp(const float* t, float l) {
  const float f = (l - kLogMin) / kStep;
  if (f <= 0) return t[0];
  if (f >= float(kNodes - 1)) return t[kNodes - 1];
  const int i = int(f);
  return t[i] + (t[i + 1] - t[i]) * (f - float(i));
}

// Radiance to display-linear RGB: the curve maps the luminance, the colour ratios are raised
// to the correction exponent (desaturating where the curve compresses contrast).
HDRF_HD Float3 ApplyCurve(Float3 rgb, const CurveLut& c) {
  const float lum = fmaxf(Luminance(rgb), c.floor);
  const float l = ClampedLog10(lum, c.floor);
  const float out = Interp(c.lum, l), s = Interp(c.sat, l);
  const float v[3] = {rgb.x, rgb.y, rgb.z};
  float d[3];
  for (int k = 0; k < 3; ++k) {
    const float ratio = fmaxf(v[k] / lum, kMinLum);
    const float disp = powf(ratio, s) * out;
    d[k] = fminf(fmaxf((disp - c.offset) / c.range, 0.f), 1.f);
  }
  return {d[0], d[1], d[2]};
}

}  // namespace hdrf::tonemap::m08
