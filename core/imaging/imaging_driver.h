// Per-frame image steps written once for both devices (common/parallel.h): the bilateral
// depth filter and the brightness-constancy tracker's grey image. The CPU runs them with
// par::Host (imaging.cpp, the CPU backend), the GPU with par::Gpu (imaging_cuda.cu).
#pragma once

#include "common/image_view.h"
#include "common/parallel.h"
#include "imaging/imaging_impl.h"

namespace hdrf::imaging {

// The CPU's filter (imaging.cpp): BilateralPixel per pixel, four neighbours of a row at once
// where their windows lie inside the image (each pixel's taps in BilateralPixel's order, one
// pixel a lane: the same bits). The GPU's is BilateralFilterOnGpu.
void BilateralFilter(par::Host, ImageView<const float> depth_m, const BilateralTables& t, ImageView<float> out);

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
