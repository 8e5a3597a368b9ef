// Colour frame -> linear radiance through the inverse camera response.
#pragma once

#include "common/cuda_runtime.h"
#include "common/image.h"
#include "radiometry/response.h"

namespace hdrf::radiometry {

// out(x, y) = f^-1(color(x, y)) / exposure_ms per channel: scene radiance L when the
// exposure is known, R (= L * exposure) when exposure_ms is 1. Runs on `device`.
void ConvertToRadiance(const ColorImage& color, const InverseResponse& inverse, float exposure_ms,
                       RadianceImage& out, Device device = Device::kCpu);

namespace detail {
void ConvertToRadianceCpu(const ColorImage& color, const float* inv_tables, float inv_exposure,
                          RadianceImage& out);
void ConvertToRadianceCuda(const ColorImage& color, const float* inv_tables, float inv_exposure,
                           RadianceImage& out);
}  // namespace detail

}  // namespace hdrf::radiometry
