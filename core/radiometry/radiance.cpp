#include "radiometry/radiance.h"

#include <cmath>

#include "common/error.h"

namespace hdrf::radiometry {

void ConvertToRadiance(const ColorImage& color, const InverseResponse& inverse, float exposure_ms,
                       RadianceImage& out, Device device) {
  if (!(exposure_ms > 0.f) || !std::isfinite(exposure_ms))
    throw Error("radiance conversion: exposure must be a positive number of milliseconds, got " +
                std::to_string(exposure_ms));
  if (out.width() != color.width() || out.height() != color.height())
    out = RadianceImage(color.width(), color.height());
  const auto tables = inverse.Flat();
  if (device == Device::kCuda) {
#if HDRF_HAS_CUDA
    detail::ConvertToRadianceCuda(color, tables.data(), 1.0f / exposure_ms, out);
#else
    ThrowNoCudaBackend();
#endif
  } else {
    detail::ConvertToRadianceCpu(color, tables.data(), 1.0f / exposure_ms, out);
  }
}

}  // namespace hdrf::radiometry
