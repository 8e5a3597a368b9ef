// Simple display mappings used by reports and previews: the global photographic operator
// (Reinhard et al. 2002) for HDR radiance, and a perceptual colour map for depth.
#pragma once

#include "common/image.h"
#include "tonemap/reinhard/reinhard.h"

namespace hdrf::tonemap {

// sRGB encoding of a linear value in [0, 1].
float SrgbEncode(float linear);

// Log-average luminance (Rec. 709) of the finite, positive pixels; 1 where there are none.
float LogAverageLuminance(const Float3* rgb, std::size_t n);

// Global Reinhard operator: scales the image so that its log-average luminance maps to
// `key`, applies ReinhardPixel, encodes sRGB.
ColorImage Reinhard(const RadianceImage& radiance, float key = 0.18f);

// Depth in metres to colour (near = yellow, far = dark blue; 0 = no data is black) over
// [min_m, max_m].
ColorImage ColorizeDepth(const DepthImage& depth_m, float min_m, float max_m);

}  // namespace hdrf::tonemap
