#include "radiometry/radiance.h"

#include <array>
#include <cmath>

#include "common/error.h"
#include "radiometry/radiance_driver.h"

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

void ConvertFrame(const ColorImage& color, const InverseResponse& inv,
                  const PcfTables& pcf, int k, RadianceImage& radiance,
                  Image<float>& confidence, Image<float>& max_confidence, Device device) {
  if (k < 0 || k > 3) throw SettingError("pcf", "must be 0, 1, 2 or 3 (p0..p3)");
  const int w = color.width(), h = color.height();
  if (radiance.width() != w || radiance.height() != h) radiance = RadianceImage(w, h);
  if (confidence.width() != w || confidence.height() != h) confidence = Image<float>(w, h);
  if (max_confidence.width() != w || max_confidence.height() != h) max_confidence = Image<float>(w, h);
  const auto inverse = inv.Flat();
  std::array<float, 3 * 256> p{};
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) p[std::size_t(c * 256 + i)] = pcf[k][c][i];
  if (device == Device::kCuda) {
#if HDRF_HAS_CUDA
    detail::ConvertFrameCuda(color, inverse.data(), p.data(), radiance, confidence, max_confidence);
    return;
#else
    ThrowNoCudaBackend();
#endif
  }
  ConvertFrameViews(par::Host{}, View(color), inverse.data(), p.data(), View(radiance), View(confidence),
                    View(max_confidence));
}

}  // namespace hdrf::radiometry
