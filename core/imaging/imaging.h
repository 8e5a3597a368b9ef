// Per-frame image processing: radiance and confidence, normalized radiance, pyramids, depth
// filtering, vertex and normal maps (ARCHITECTURE.md steps 2-3).
#pragma once

#include <vector>

#include "common/camera.h"
#include "common/cuda_runtime.h"
#include "common/image.h"
#include "imaging/imaging_impl.h"
#include "radiometry/pcf.h"
#include "radiometry/response.h"

namespace hdrf::imaging {

// Radiance R = f^-1(I) per channel (no division by exposure: the engine works in the
// radiance units of the live frame and estimates exposure ratios itself), and the
// confidence of each pixel: the mean over channels of PCF p_k (k = pcf_power, 0..3), with
// saturated or black channels (level 255 or 0) given confidence 0.
// Runs on `device` (the CUDA version is checked against this one by tests/gpu).
void ConvertFrame(const ColorImage& color, const radiometry::InverseResponse& inverse,
                  const radiometry::PcfTables& pcf, int pcf_power, RadianceImage& radiance,
                  Image<float>& confidence, Image<float>& max_confidence,
                  Device device = Device::kCpu);

namespace detail {
void ConvertFrameCuda(const ColorImage& color, const float* inverse, const float* pcf,
                      RadianceImage& radiance, Image<float>& confidence, Image<float>& max_confidence);
}  // namespace detail

// Luminance of a radiance image (Rec. 709).
Image<float> Luminance(const RadianceImage& radiance);

struct NormalizedRadianceOptions {
  int patch = 15;       // side of the local patch N, in pixels of the down-sampled image
  int downsample = 2;   // local statistics on an image down-sampled by this factor
  float min_std = 1e-3f;  // relative floor on the local std (flat, noise-only patches)
};

// Normalized radiance (R - mean_N(R)) / std_N(R) of a luminance image, with the local mean
// and std from integral images of a down-sampled copy (cost independent of the patch size),
// bilinearly up-sampled. Pixels with value <= 0 (no data) are left out of the statistics and
// get NR = 0. min_std is relative to the local mean.
Image<float> NormalizedRadiance(const Image<float>& luminance, const NormalizedRadianceOptions& o,
                                Image<float>* local_mean = nullptr,
                                Image<float>* local_std = nullptr);

// Image pyramids: each level half the size of the one before.
Image<float> Downsample(const Image<float>& img);         // 2x2 mean
DepthImage DownsampleDepth(const DepthImage& depth);      // mean of valid neighbours close in depth

// Weight tables of the bilateral filter (radius 1..kBilateralMaxRadius).
BilateralTables MakeBilateralTables(float sigma_space_px, float sigma_depth_m, int radius);
// Edge-preserving bilateral filter of a depth map (metres; 0 = no data stays 0).
DepthImage BilateralDepth(const DepthImage& depth, float sigma_space_px = 2.0f,
                          float sigma_depth_m = 0.03f, int radius = 3);

// Camera-frame vertex map (0,0,0 where no depth) and normal map (0,0,0 where undefined).
Image<Float3> VertexMap(const DepthImage& depth, const PinholeCamera& cam);
Image<Float3> NormalMap(const Image<Float3>& vertices, float max_jump_m = 0.1f);

// Bilinear sample; false when a needed neighbour is outside or has value <= invalid.
bool SampleBilinear(const Image<float>& img, float x, float y, float* out);

}  // namespace hdrf::imaging
