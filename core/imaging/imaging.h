// Per-frame image processing: depth filtering, pyramid steps, vertex and normal maps.
// (Radiance and confidence: radiometry/radiance.h; normalized radiance:
// normalized_radiance/normalized_radiance.h.)
#pragma once

#include <vector>

#include "common/camera.h"
#include "common/cuda_runtime.h"
#include "common/image.h"
#include "imaging/imaging_impl.h"
#include "radiometry/pcf.h"
#include "radiometry/response.h"

namespace hdrf::imaging {

// Filtering of the depth before tracking and fusion, and the normal maps made from it.
struct DepthFilterOptions {
  bool bilateral = true;           // edge-preserving bilateral filter of the depth
  float sigma_space_px = 2.0f;     // its spatial sigma, pixels
  float sigma_depth_m = 0.03f;     // its range sigma, metres
  int radius = 3;                  // its window radius, pixels (1..kBilateralMaxRadius)
  float max_normal_jump_m = 0.1f;  // normals are undefined across depth jumps larger than this
  void Check() const;              // throws SettingError naming the setting
};

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
