// Per-pixel radiance conversion, shared by the CPU loop and the CUDA kernel.
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

}  // namespace hdrf::radiometry
