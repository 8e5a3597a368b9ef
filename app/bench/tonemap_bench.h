// The tone-mapping speed benchmark: each Mantiuk operator (and Reinhard, for scale) on
// given HDR images, per device, mean milliseconds per frame including the transfers. Used
// by `hdrfusion bench --suite tonemap` (OpenEXR images, beside pfstmo) and by
// `hdrfusion-bench --suite tonemap` (synthetic frames, core only: the GPU machine).
#pragma once

#include <string>
#include <vector>

#include "common/cuda_runtime.h"
#include "common/image.h"

namespace hdrf::bench {

struct TonemapRow {
  std::string image, op;
  Device device;
  double ms = 0;
  int iterations = 0;  // mantiuk06: the solver's iterations on the last frame
};

// Each image is resampled to 640x480 by the caller. `frames` timed after one warm-up
// (mantiuk06 on the CPU: a tenth, at least one).
std::vector<TonemapRow> RunTonemapBench(const std::vector<std::pair<std::string, const RadianceImage*>>& images,
                                        int frames, const std::vector<Device>& devices);

// Area resampling to w x h.
RadianceImage Resample(const RadianceImage& in, int w, int h);

// Synthetic HDR test frames at 640x480 (the room and the desk scenes' true radiance).
std::vector<std::pair<std::string, RadianceImage>> SyntheticHdrFrames();

}  // namespace hdrf::bench
