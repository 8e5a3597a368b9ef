// Structural similarity (Wang et al. 2004) of two single-channel images with values in
// [0, 1]: an 11 x 11 Gaussian window (sigma 1.5), constants (0.01)^2 and (0.03)^2, averaged
// over the positions where the window lies inside the image.
#pragma once

#include "common/image.h"

namespace hdrf::eval {

// Throws Error when the sizes differ or the images are smaller than the window.
double Ssim(const Image<float>& a, const Image<float>& b);

// Rec. 709 luminance of display-encoded RGB, per pixel (what "SSIM of luminance" compares).
Image<float> LuminanceOf(const Image<Float3>& rgb);

}  // namespace hdrf::eval
