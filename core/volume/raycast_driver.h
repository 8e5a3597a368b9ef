// Ray casting (the paper's step 7), written once for both devices (common/parallel.h): each
// pixel's ray (raycast_impl.h) into the rendering's images. Volume::Raycast runs it with
// par::Host, DeviceVolume::Raycast (volume_cuda.cu) with par::Gpu.
#pragma once

#include <type_traits>

#include "common/image_view.h"
#include "common/parallel.h"
#include "volume/raycast_impl.h"
#include "volume/volume_impl.h"

namespace hdrf::volume {

struct RenderingViews {
  ImageView<Float3> vertex, normal, radiance;
  ImageView<float> nr, depth;
  HDRF_HD void Set(int x, int y, const RayHit& hit) const {
    vertex(x, y) = hit.vertex;
    normal(x, y) = hit.normal;
    radiance(x, y) = hit.radiance;
    nr(x, y) = hit.nr;
    depth(x, y) = hit.depth;
  }
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

// The ray cast in two passes over the pixels: each ray's walk to its crossing (MarchRay, its
// distance kept in the depth image), then the hits' shading (ShadeCrossing, which writes
// every image). The same images as one pass (the hint of the walk's last brick spares
// look-ups only). On the GPU the two kernels take about half one pass's time (measured on an
// H200 at 640x480: 181 us against 338): they run a fifth fewer instructions, and each needs
// fewer registers (48 and 56 against 63) and keeps more of a warp's threads busy.
template <typename Device, typename V>
void RaycastInTwoPasses(Device d, const VolumeView<V>& volume, const RaycastArgs& a, const RenderingViews& out) {
  const VolumeView<V> vv = volume;
  const RaycastArgs args = a;
  const RenderingViews r = out;
  par::ForEachPixelInTiles(d, a.cam.width, a.cam.height, HDRF_LAMBDA(int x, int y) {
    r.depth(x, y) = MarchRay(vv, args, x, y, RayOfPixel(args, x, y));
  });
  par::ForEachPixelInTiles(d, a.cam.width, a.cam.height, HDRF_LAMBDA(int x, int y) {
    const float ts = r.depth(x, y);
    r.Set(x, y, ts >= 0.f ? ShadeCrossing(vv, RayOfPixel(args, x, y), ts, typename VolumeView<V>::BrickHint{}) : RayHit{});
  });
}

// The ray cast into the rendering's images: on the CPU one pass (each ray walked and shaded
// in turn, the walk's last brick reused), on the GPU two (RaycastInTwoPasses).
template <typename Device, typename V>
void RaycastInto(Device d, const VolumeView<V>& volume, const RaycastArgs& a, const RenderingViews& out) {
  if constexpr (!std::is_same_v<Device, par::Host>) {
    RaycastInTwoPasses(d, volume, a, out);
  } else {
    const VolumeView<V> vv = volume;
    const RaycastArgs args = a;
    const RenderingViews r = out;
    par::ForEachPixelInTiles(d, a.cam.width, a.cam.height, HDRF_LAMBDA(int x, int y) { r.Set(x, y, RaycastPixel(vv, args, x, y)); });
  }
}

}  // namespace hdrf::volume
