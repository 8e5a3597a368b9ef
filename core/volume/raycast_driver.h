// Ray casting (the paper's step 7), written once for both devices (common/parallel.h): one
// RaycastPixel (volume_impl.h) per pixel into the rendering's images. Volume::Raycast runs it
// with par::Host, DeviceVolume::Raycast (volume_cuda.cu) with par::Gpu.
#pragma once

#include "common/image_view.h"
#include "common/parallel.h"
#include "volume/volume_impl.h"

namespace hdrf::volume {

struct RenderingViews {
  ImageView<Float3> vertex, normal, radiance;
  ImageView<float> nr, depth;
};

template <typename Device, typename V>
void RaycastInto(Device d, const VolumeView<V>& volume, const RaycastArgs& a, const RenderingViews& out) {
  const VolumeView<V> vv = volume;
  const RaycastArgs args = a;
  const RenderingViews r = out;
  par::ForEachPixel(d, a.cam.width, a.cam.height, HDRF_LAMBDA(int x, int y) {
    const RayHit hit = RaycastPixel(vv, args, x, y);
    r.vertex(x, y) = hit.vertex;
    r.normal(x, y) = hit.normal;
    r.radiance(x, y) = hit.radiance;
    r.nr(x, y) = hit.nr;
    r.depth(x, y) = hit.depth;
  });
}

}  // namespace hdrf::volume
