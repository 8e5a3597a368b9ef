// Ray casting (the paper's step 7), written once for both devices (common/parallel.h): one
// RaycastPixel (volume_impl.h) per pixel into the rendering's images. Volume::Raycast runs it
// with par::Host, DeviceVolume::Raycast (volume_cuda.cu) with par::Gpu.
#pragma once

#include "common/image_view.h"
#include "common/parallel.h"
#include "volume/raycast_impl.h"
#include "volume/volume_impl.h"

namespace hdrf::volume {

struct RenderingViews {
  ImageView<Float3> vertex, normal, radiance;
  ImageView<float> nr, depth;
};

// The ray cast's guide from a depth image taken at the pose the model is ray cast from (the
// frame just fused): per tile of kGuideTile x kGuideTile pixels, the nearest depth less
// `margin_m` where every pixel of the tile has depth, else 0 (the tile's rays start at near).
// A surface of the model nearer than that is one the camera did not see in front of it now.
// `tiles` is ceil(w / kGuideTile) x ceil(h / kGuideTile).
template <typename Device>
void RaycastGuide(Device d, ImageView<const float> depth, float margin_m, const ImageView<float>& tiles) {
  const ImageView<const float> in = depth;
  const ImageView<float> out = tiles;
  const float margin = margin_m;
  par::ForEachPixel(d, tiles.width, tiles.height, HDRF_LAMBDA(int tx, int ty) {
    float lo = 1e30f;
    bool all = true;
    for (int y = ty * kGuideTile; y < ty * kGuideTile + kGuideTile && y < in.height; ++y)
      for (int x = tx * kGuideTile; x < tx * kGuideTile + kGuideTile && x < in.width; ++x) {
        const float z = in(x, y);
        if (!(z > 0.f)) all = false;
        lo = z < lo ? z : lo;
      }
    const float s = lo - margin;
    out(tx, ty) = all && s > 0.f ? s : 0.f;
  });
}

template <typename Device, typename V>
void RaycastInto(Device d, const VolumeView<V>& volume, const RaycastArgs& a, const RenderingViews& out) {
  const VolumeView<V> vv = volume;
  const RaycastArgs args = a;
  const RenderingViews r = out;
  par::ForEachPixelInTiles(d, a.cam.width, a.cam.height, HDRF_LAMBDA(int x, int y) {
    const RayHit hit = RaycastPixel(vv, args, x, y);
    r.vertex(x, y) = hit.vertex;
    r.normal(x, y) = hit.normal;
    r.radiance(x, y) = hit.radiance;
    r.nr(x, y) = hit.nr;
    r.depth(x, y) = hit.depth;
  });
}

}  // namespace hdrf::volume
