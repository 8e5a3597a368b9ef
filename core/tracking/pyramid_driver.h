// The tracker's pyramids, written once for both devices (common/parallel.h): the live
// frame's levels (depth, intensity and weight halved; vertices, gradients and normals per
// level) and the reference's levels (vertices and normals subsampled, intensity halved).
// The CPU entry points (MakeLive, MakeReference in tracking.cpp) run them with par::Host;
// the CUDA backend with par::Gpu (tracking_cuda.cu).
#pragma once

#include "common/camera.h"
#include "common/image_view.h"
#include "common/parallel.h"
#include "common/vec.h"
#include "imaging/imaging_impl.h"

namespace hdrf::tracking {

struct LiveLevelViews {
  PinholeCamera cam;
  ImageView<float> depth, intensity, weight, grad_x, grad_y;
  ImageView<Float3> vertex, normal;
};
struct ReferenceLevelViews {
  PinholeCamera cam;
  ImageView<Float3> vertex, normal;  // world frame; zero = none
  ImageView<float> intensity;
};

// Level L of the live pyramid; its depth, intensity and weight are first made from `finer`
// (the level above, twice the size) where there is one, else they hold the frame's.
template <typename Device>
void BuildLiveLevel(Device d, const LiveLevelViews* finer, const LiveLevelViews& L, float max_normal_jump_m) {
  const ImageView<float> depth = L.depth, in = L.intensity, wt = L.weight, gx = L.grad_x, gy = L.grad_y;
  const ImageView<Float3> v = L.vertex, n = L.normal;
  const PinholeCamera cam = L.cam;
  const int w = cam.width, h = cam.height;
  if (finer) {
    const ImageView<const float> pd = finer->depth, pi = finer->intensity, pw = finer->weight;
    par::ForEachPixel(d, w, h, HDRF_LAMBDA(int x, int y) {
      depth(x, y) = imaging::DownsampleDepthPixel(pd, x, y);
      in(x, y) = imaging::Mean2x2(pi, x, y);
      wt(x, y) = imaging::Mean2x2(pw, x, y);
    });
  }
  const ImageView<const float> dc = depth, ic = in;
  par::ForEachPixel(d, w, h, HDRF_LAMBDA(int x, int y) {
    v(x, y) = imaging::VertexPixel(dc, cam, x, y);
    gx(x, y) = imaging::GradXPixel(ic, x, y);
    gy(x, y) = imaging::GradYPixel(ic, x, y);
  });
  const ImageView<const Float3> vc = v;
  par::ForEachPixel(d, w, h, HDRF_LAMBDA(int x, int y) { n(x, y) = imaging::NormalPixel(vc, max_normal_jump_m, x, y); });
}

// Level L of the reference pyramid from the level above.
template <typename Device>
void BuildReferenceLevel(Device d, const ReferenceLevelViews& finer, const ReferenceLevelViews& L) {
  const ImageView<const Float3> pv = finer.vertex, pn = finer.normal;
  const ImageView<const float> pi = finer.intensity;
  const ImageView<Float3> v = L.vertex, n = L.normal;
  const ImageView<float> in = L.intensity;
  par::ForEachPixel(d, L.cam.width, L.cam.height, HDRF_LAMBDA(int x, int y) {
    v(x, y) = pv(2 * x, 2 * y);
    n(x, y) = pn(2 * x, 2 * y);
    in(x, y) = imaging::Mean2x2(pi, x, y);
  });
}

// The finest live level placed in the world at a pose (frame-to-frame tracking's
// reference): vertices and normals where both are defined, zero elsewhere.
template <typename Device>
void PlaceInWorld(Device d, ImageView<const Float3> vertex_c, ImageView<const Float3> normal_c,
                  const RigidTransform& T_world_camera, ImageView<Float3> vertex_w, ImageView<Float3> normal_w) {
  par::ForEachPixel(d, vertex_c.width, vertex_c.height, HDRF_LAMBDA(int x, int y) {
    const bool ok = vertex_c(x, y).z > 0.f && Length(normal_c(x, y)) > 0.f;
    vertex_w(x, y) = ok ? T_world_camera.Apply(vertex_c(x, y)) : Float3{0, 0, 0};
    normal_w(x, y) = ok ? T_world_camera.Rotate(normal_c(x, y)) : Float3{0, 0, 0};
  });
}

}  // namespace hdrf::tracking
