// Pinhole camera: x right, y down, z forward (OpenCV/TUM convention), pixel centres at
// integer coordinates.
#pragma once

#include "common/host_device.h"
#include "common/vec.h"

namespace hdrf {

struct PinholeCamera {
  int width = 0;
  int height = 0;
  float fx = 0, fy = 0, cx = 0, cy = 0;

  // Pixel (u, v) of a camera-frame point; z must be > 0.
  HDRF_HD Float2 Project(Float3 p) const {
    const float inv_z = 1.0f / p.z;
    return {fx * p.x * inv_z + cx, fy * p.y * inv_z + cy};
  }
  // Camera-frame point at depth z_m along the ray through pixel (u, v).
  HDRF_HD Float3 BackProject(float u, float v, float z_m) const {
    return {(u - cx) / fx * z_m, (v - cy) / fy * z_m, z_m};
  }
  HDRF_HD bool Contains(Float2 px) const {
    return px.x >= 0.f && px.y >= 0.f && px.x <= float(width - 1) && px.y <= float(height - 1);
  }
  // The camera of an image down-sampled by `factor` (2 for one pyramid level): pixel
  // centres map as u' = (u + 0.5) / factor - 0.5.
  HDRF_HD PinholeCamera Scaled(int factor) const {
    const float s = 1.0f / float(factor);
    return {width / factor, height / factor, fx * s, fy * s, (cx + 0.5f) * s - 0.5f,
            (cy + 0.5f) * s - 0.5f};
  }
  bool Valid() const { return width > 0 && height > 0 && fx > 0 && fy > 0; }
};

}  // namespace hdrf
