// Per-pixel step of exposure compensation (the paper's step 5), shared by the CPU
// (exposure.cpp) and the GPU (exposure_cuda.cu).
#pragma once

#include "common/camera.h"
#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"

namespace hdrf::exposure {

// One sample of the exposure-ratio estimate at model pixel (x, y): log(model / live)
// luminance and the live confidence as weight; false where there is no usable pair.
struct ExposureArgs {
  ImageView<const Float3> model_vertex;    // world frame
  ImageView<const Float3> model_radiance;
  ImageView<const Float3> live_radiance;
  ImageView<const float> live_confidence;
  PinholeCamera cam;
  RigidTransform T_live_world;
};
HDRF_HD bool ExposureSample(const ExposureArgs& a, int x, int y, float* log_ratio, float* weight) {
  const Float3 m = a.model_vertex(x, y);
  const float lm = Luminance(a.model_radiance(x, y));
  if (!(lm > 0.f) || (m.x == 0.f && m.y == 0.f && m.z == 0.f)) return false;
  const Float3 q = a.T_live_world.Apply(m);
  if (q.z <= 0.1f) return false;
  const Float2 u = a.cam.Project(q);
  const int ux = RoundToInt(u.x), uy = RoundToInt(u.y);
  if (ux < 0 || uy < 0 || ux >= a.cam.width || uy >= a.cam.height) return false;
  const float wl = a.live_confidence(ux, uy);
  const float ll = Luminance(a.live_radiance(ux, uy));
  if (wl <= 0.f || !(ll > 0.f)) return false;
  *log_ratio = logf(lm / ll);
  *weight = wl;
  return true;
}

}  // namespace hdrf::exposure
