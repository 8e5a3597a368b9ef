// Per-pixel steps of imaging, shared by the CPU loops and the CUDA kernels.
#pragma once

#include "common/host_device.h"
#include "common/image.h"
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

}  // namespace hdrf::imaging
