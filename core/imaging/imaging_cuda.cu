#include "common/parallel_cuda.cuh"
#include "imaging/imaging_driver.h"

namespace hdrf::imaging {

void BilateralFilterOnGpu(ImageView<const float> depth_m, const BilateralTables& t, ImageView<float> out) {
  BilateralFilter(par::Gpu{}, depth_m, t, out);
}

void RawIntensityOnGpu(ImageView<const Rgb8> color, ImageView<float> intensity, ImageView<float> weight) {
  RawIntensity(par::Gpu{}, color, intensity, weight);
}

}  // namespace hdrf::imaging
