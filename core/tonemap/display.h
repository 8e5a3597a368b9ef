// Simple display mappings used by reports and previews: the global photographic operator
// (Reinhard et al. 2002) for HDR radiance, and a perceptual colour map for depth.
#pragma once

#include "common/image.h"

namespace hdrf::tonemap {

// sRGB encoding of a linear value in [0, 1].
float SrgbEncode(float linear);

// Global Reinhard operator: scales the image so that its log-average luminance maps to
// `key`, compresses L / (1 + L), keeps colour ratios, encodes sRGB. Non-finite and
// negative input maps to black.
ColorImage Reinhard(const RadianceImage& radiance, float key = 0.18f);

// Depth in metres to colour (near = yellow, far = dark blue; 0 = no data is black) over
// [min_m, max_m].
ColorImage ColorizeDepth(const DepthImage& depth_m, float min_m, float max_m);

}  // namespace hdrf::tonemap
