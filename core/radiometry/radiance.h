// Colour frame -> linear radiance through the inverse camera response.
#pragma once

#include "common/cuda_runtime.h"
#include "common/image.h"
#include "radiometry/pcf.h"
#include "radiometry/response.h"

namespace hdrf::radiometry {

// out(x, y) = f^-1(color(x, y)) / exposure_ms per channel: scene radiance L when the
// exposure is known, R (= L * exposure) when exposure_ms is 1. Runs on `device`.
void ConvertToRadiance(const ColorImage& color, const InverseResponse& inverse, float exposure_ms,
                       RadianceImage& out, Device device = Device::kCpu);

// Radiance R = f^-1(I) per channel (no division by exposure: the engine works in the
// radiance units of the live frame and estimates exposure ratios itself), and the
// confidence of each pixel: the mean over channels of PCF p_k (k = pcf_power, 0..3), with
// saturated or black channels (level 255 or 0) given confidence 0.
// Runs on `device` (the CUDA version is checked against this one by tests/gpu).
void ConvertFrame(const ColorImage& color, const InverseResponse& inverse,
                  const PcfTables& pcf, int pcf_power, RadianceImage& radiance,
                  Image<float>& confidence, Image<float>& max_confidence,
                  Device device = Device::kCpu);

namespace detail {
void ConvertFrameCuda(const ColorImage& color, const float* inverse, const float* pcf,
                      RadianceImage& radiance, Image<float>& confidence, Image<float>& max_confidence);
void ConvertToRadianceCpu(const ColorImage& color, const float* inv_tables, float inv_exposure,
                          RadianceImage& out);
void ConvertToRadianceCuda(const ColorImage& color, const float* inv_tables, float inv_exposure,
                           RadianceImage& out);
}  // namespace detail

}  // namespace hdrf::radiometry
