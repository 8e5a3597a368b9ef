// The normalized-radiance driver, written once for both devices (common/parallel.h): the
// CPU entry point (normalized_radiance.cpp) runs it with par::Host, the CUDA backend with
// par::Gpu (normalized_radiance_cuda.cu, which also gives the GPU its own row pass).
#pragma once

#include "common/parallel.h"
#include "common/vec.h"
#include "normalized_radiance/normalized_radiance.h"

namespace hdrf::nr {

// Work images on the down-sampled grid (sw x sh cells, integrals (sw+1) x (sh+1)), on the
// device the driver runs on.
struct Scratch {
  ImageView<float> cells, mean_s, std_s;
  NrIntegrals in;
};

// The live frame's luminance for tracking (Rec. 709, what normalized radiance is computed
// on), 0 (no data) where any channel of the pixel is clipped at 255, and the tracking
// weight there 0 too. A clipped pixel's
// radiance is only a lower bound that moves with the exposure (a window, a lamp): inside a
// patch's statistics it shifts the normalized radiance of the unclipped pixels beside it,
// while the model's ray cast has no such pixels (a window has no depth), so the photometric
// term pulls the pose across the clipped region's border. Kept out, both sides normalize
// over the same kind of pixels. (The clipped pixels' values, normalized by their unclipped
// surround, would be large beside the border, where the tracker samples and differentiates
// the image.)
HDRF_HD bool PixelClipped(Rgb8 c) { return c.r == 255 || c.g == 255 || c.b == 255; }
template <typename Device>
void TrackingLuminanceOf(Device d, ImageView<const Rgb8> color, ImageView<const Float3> radiance,
                         ImageView<const float> confidence, ImageView<float> lum, ImageView<float> weight) {
  par::ForEachPixel(d, radiance.width, radiance.height, HDRF_LAMBDA(int x, int y) {
    const bool clipped = PixelClipped(color(x, y));
    lum(x, y) = clipped ? 0.f : hdrf::Luminance(radiance(x, y));
    weight(x, y) = clipped ? 0.f : confidence(x, y);
  });
}

// The model's luminance for tracking a live frame: 0 (no data) where any channel of the
// model's radiance reaches `clip`, the live frame's clipping level in model units (where the
// live frame reads 255 and TrackingLuminanceOf leaves the pixel out): the two sides then
// normalize over the same pixels, also where the live exposure clips surfaces the model holds.
HDRF_HD float ClippedLuminance(Float3 r, Float3 clip) {
  return (r.x >= clip.x || r.y >= clip.y || r.z >= clip.z) ? 0.f : hdrf::Luminance(r);
}
template <typename Device>
void ClippedLuminanceOf(Device d, ImageView<const Float3> radiance, Float3 clip, ImageView<float> lum) {
  par::ForEachPixel(d, radiance.width, radiance.height,
                    HDRF_LAMBDA(int x, int y) { lum(x, y) = ClippedLuminance(radiance(x, y), clip); });
}

// The row and column passes of the integral images on the CPU: each row, then each column,
// is independent.
inline void RowPasses(par::Host d, ImageView<const float> cells, NrIntegrals in) {
  par::ForEach(d, cells.height, [=](int y) { NrRowPass(cells, in, y); });
}
inline void ColumnPasses(par::Host d, NrIntegrals in) {
  par::ForEach(d, in.cnt.width, [=](int x) { NrColumnPass(in, x); });
}

// NR of `lum` into `out`; the up-sampled local mean and std too where those views are
// non-empty. The passes of the integral images are device-specific (RowPasses, ColumnPasses,
// found for the device's tag).
template <typename Device>
void Normalize(Device d, ImageView<const float> lum, const Scratch& s, const NormalizedRadianceOptions& o,
               ImageView<float> out, ImageView<float> mean_out = {}, ImageView<float> std_out = {}) {
  const int f = o.downsample, r = o.patch / 2;
  const float min_std = o.min_std;
  const ImageView<float> cells = s.cells, ms = s.mean_s, ss = s.std_s;
  const NrIntegrals in = s.in;
  // 1. Cell means, 2. integral images, 3. local statistics on the small grid.
  par::ForEachPixel(d, cells.width, cells.height, HDRF_LAMBDA(int x, int y) { cells(x, y) = NrCellMean(lum, x, y, f); });
  RowPasses(d, ImageView<const float>(cells), in);
  ColumnPasses(d, in);
  par::ForEachPixel(d, cells.width, cells.height,
                    HDRF_LAMBDA(int x, int y) { NrLocalStats(in, x, y, r, &ms(x, y), &ss(x, y)); });
  // 4. Up-sampled statistics and the normalized value per pixel.
  const ImageView<const float> msc = ms, ssc = ss;
  par::ForEachPixel(d, lum.width, lum.height, HDRF_LAMBDA(int x, int y) {
    NrPixel(lum, msc, ssc, f, min_std, x, y, &out(x, y), mean_out.data ? &mean_out(x, y) : nullptr,
            std_out.data ? &std_out(x, y) : nullptr);
  });
}

// The same drivers on the GPU (normalized_radiance_cuda.cu), over device views.
void ClippedLuminanceOnGpu(ImageView<const Float3> radiance, Float3 clip, ImageView<float> lum);
void TrackingLuminanceOnGpu(ImageView<const Rgb8> color, ImageView<const Float3> radiance,
                            ImageView<const float> confidence, ImageView<float> lum, ImageView<float> weight);
void NormalizeOnGpu(ImageView<const float> lum, const Scratch& s, const NormalizedRadianceOptions& o,
                    ImageView<float> out);

}  // namespace hdrf::nr
