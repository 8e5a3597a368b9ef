// Normalized radiance (the paper's step 3): (R - mean_N(R)) / std_N(R) of the luminance over a
// local patch N, which does not depend on the exposure. The local statistics come from
// integral images of a down-sampled copy, so the cost does not depend on the patch size.
#pragma once

#include "common/image.h"
#include "common/image_view.h"
#include "normalized_radiance/normalized_radiance_impl.h"

namespace hdrf::nr {

// Luminance of a radiance image (Rec. 709).
Image<float> Luminance(const RadianceImage& radiance);

struct NormalizedRadianceOptions {
  int patch = 15;       // side of the local patch N, in pixels of the down-sampled image
  int downsample = 2;   // local statistics on an image down-sampled by this factor
  float min_std = 1e-3f;  // relative floor on the local std (flat, noise-only patches)
  void Check() const;     // throws SettingError naming the setting (nr.*)
};

// Normalized radiance (R - mean_N(R)) / std_N(R) of a luminance image, with the local mean
// and std from integral images of a down-sampled copy (cost independent of the patch size),
// bilinearly up-sampled. Pixels with value <= 0 (no data) are left out of the statistics and
// get NR = 0. min_std is relative to the local mean.
Image<float> NormalizedRadiance(const Image<float>& luminance, const NormalizedRadianceOptions& o,
                                Image<float>* local_mean = nullptr,
                                Image<float>* local_std = nullptr);

}  // namespace hdrf::nr
