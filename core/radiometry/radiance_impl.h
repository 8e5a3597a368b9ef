// Per-pixel radiance conversion (the paper's step 2), the one definition every path uses:
// `hdrfusion radiance`, ConvertFrame, and the engine's CPU and CUDA backends.
#pragma once

#include "common/camera.h"
#include "common/host_device.h"
#include "common/image.h"

namespace hdrf::radiometry {

// R / exposure: radiance of one pixel through channel-major inverse tables (3 x 256).
HDRF_HD Float3 PixelRadiance(Rgb8 c, const float* inv_tables, float inv_exposure) {
  return {inv_tables[c.r] * inv_exposure, inv_tables[256 + c.g] * inv_exposure,
          inv_tables[512 + c.b] * inv_exposure};
}

// Radiance f^-1(I) and confidence of one pixel: `inverse` and `pcf` are channel-major
// 3 x 256 tables (the chosen PCF variant); levels 0 and 255 carry no confidence.
HDRF_HD void ConvertPixel(Rgb8 c, const float* inverse, const float* pcf, Float3* radiance,
                          float* confidence, float* max_confidence) {
  *radiance = PixelRadiance(c, inverse, 1.f);  // R itself: x * 1 is exact
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

}  // namespace hdrf::radiometry
