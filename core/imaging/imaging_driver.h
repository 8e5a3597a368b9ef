// Per-frame image steps written once for both devices (common/parallel.h): the bilateral
// depth filter and the brightness-constancy tracker's grey image. The CPU runs them with
// par::Host (imaging.cpp, the CPU backend), the GPU with par::Gpu (imaging_cuda.cu).
#pragma once

#include "common/image_view.h"
#include "common/parallel.h"
#include "imaging/imaging_impl.h"

namespace hdrf::imaging {

template <typename Device>
void BilateralFilter(Device d, ImageView<const float> depth_m, const BilateralTables& t, ImageView<float> out) {
  const BilateralTables tables = t;
  par::ForEachPixel(d, depth_m.width, depth_m.height,
                    HDRF_LAMBDA(int x, int y) { out(x, y) = BilateralPixel(depth_m, tables, x, y); });
}

// The delivered colour as grey in [0, 1], each pixel weighted 1.
template <typename Device>
void RawIntensity(Device d, ImageView<const Rgb8> color, ImageView<float> intensity, ImageView<float> weight) {
  par::ForEachPixel(d, color.width, color.height, HDRF_LAMBDA(int x, int y) {
    intensity(x, y) = RawIntensityPixel(color(x, y));
    weight(x, y) = 1.f;
  });
}

// `tables` in device memory (the same tables as BilateralFilter's).
void BilateralFilterOnGpu(ImageView<const float> depth_m, const BilateralTables* tables, ImageView<float> out);
void RawIntensityOnGpu(ImageView<const Rgb8> color, ImageView<float> intensity, ImageView<float> weight);

}  // namespace hdrf::imaging
