// Radiance and pixel confidence of a frame (the paper's step 2), written once for both
// devices (common/parallel.h): ConvertFrame and the CPU backend run it with par::Host, the
// CUDA backend with par::Gpu (radiance_cuda.cu).
#pragma once

#include "common/image_view.h"
#include "common/parallel.h"
#include "radiometry/radiance_impl.h"

namespace hdrf::radiometry {

// `inverse` and `pcf`: channel-major 3 x 256 tables on the device the driver runs on.
template <typename Device>
void ConvertFrameViews(Device d, ImageView<const Rgb8> color, const float* inverse, const float* pcf,
                       ImageView<Float3> radiance, ImageView<float> confidence, ImageView<float> max_confidence) {
  par::ForEachPixel(d, color.width, color.height, HDRF_LAMBDA(int x, int y) {
    ConvertPixel(color(x, y), inverse, pcf, &radiance(x, y), &confidence(x, y), &max_confidence(x, y));
  });
}

void ConvertFrameOnGpu(ImageView<const Rgb8> color, const float* inverse, const float* pcf,
                       ImageView<Float3> radiance, ImageView<float> confidence, ImageView<float> max_confidence);

}  // namespace hdrf::radiometry
