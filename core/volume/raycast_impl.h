// Per-pixel ray casting of the volume, shared by the CPU loops and the CUDA kernels
// (raycast_driver.h runs it on either device); the volume's arrays and samples are in
// volume_impl.h.
#pragma once

#include <array>

#include "volume/volume_impl.h"

namespace hdrf::volume {

// ---- Ray casting ------------------------------------------------------------------------------
struct RaycastArgs {
  PinholeCamera cam;
  RigidTransform T_world_camera;
  float near_m, far_m;
  // Where the rays may start (raycast_driver.h, RaycastGuide): per tile of kGuideTile x
  // kGuideTile pixels, a depth (m) no surface of the tile lies before; 0 or no image: near_m.
  ImageView<const float> start{};
  // The world box of the allocated bricks (Volume::Bounds); rays are cast only inside it.
  // box_lo > box_hi (the default): no box, the whole way from near to far.
  Float3 box_lo{1, 1, 1}, box_hi{0, 0, 0};
  void SetBox(const std::array<Float3, 2>& b) { box_lo = b[0], box_hi = b[1]; }
  // Or the box as the device keeps it (DeviceVolume::device_box, read by each ray: it may be
  // written by the work queued before the ray cast): brick coordinates, low x, y, z then high
  // x, y, z (low above high: no bricks), and the brick's side; the same box as BrickBox::World.
  const int* box_bricks = nullptr;
  float box_brick_m = 0;
};

// Narrows [t0, t1] along the ray o + t d (inv_d: 1 / d per axis, 1e9 where d is about 0) to
// the part inside the box; false where the ray misses it or the box is empty. No sample
// outside the box is defined (its corners inside carry less than half its weight), so the
// hits are those of the whole ray.
HDRF_HD bool ClipToBox(const RaycastArgs& a, const Float3& o, const float inv_d[3], float* t0, float* t1) {
  float lo[3] = {a.box_lo.x, a.box_lo.y, a.box_lo.z}, hi[3] = {a.box_hi.x, a.box_hi.y, a.box_hi.z};
  if (a.box_bricks) {
    const int* b = a.box_bricks;
    if (b[0] > b[3]) return false;  // no bricks
    for (int k = 0; k < 3; ++k) {
      lo[k] = float(b[k]) * a.box_brick_m;
      hi[k] = float(b[3 + k] + 1) * a.box_brick_m;
    }
  } else if (a.box_lo.x > a.box_hi.x) {
    return true;
  }
  const float op[3] = {o.x, o.y, o.z};
  if (lo[0] >= hi[0] || lo[1] >= hi[1] || lo[2] >= hi[2]) return false;  // no bricks
  float enter = *t0, leave = *t1;
  for (int k = 0; k < 3; ++k) {
    if (inv_d[k] == 1e9f) {  // parallel to this axis' faces: inside their slab or nowhere
      if (op[k] < lo[k] || op[k] > hi[k]) return false;
      continue;
    }
    const float ta = (lo[k] - op[k]) * inv_d[k], tb = (hi[k] - op[k]) * inv_d[k];
    const float tn = ta < tb ? ta : tb, tf = ta < tb ? tb : ta;
    enter = tn > enter ? tn : enter;
    leave = tf < leave ? tf : leave;
  }
  *t0 = enter;
  *t1 = leave;
  return enter < leave;
}
inline constexpr int kGuideTile = 8;
inline int GuideTiles(int pixels) { return (pixels + kGuideTile - 1) / kGuideTile; }  // tiles of a side
struct RayHit {
  Float3 vertex{0, 0, 0}, normal{0, 0, 0}, radiance{0, 0, 0};
  float nr = 0, depth = 0;
};

// Pixel (x, y)'s ray: its direction in the camera and in the world (unit length), and its origin.
struct PixelRay {
  Float3 dc, dw, o;
};
HDRF_HD PixelRay RayOfPixel(const RaycastArgs& a, int x, int y) {
  const Float3 dc = Normalized(a.cam.BackProject(float(x), float(y), 1.f));
  return {dc, a.T_world_camera.Rotate(dc), a.T_world_camera.t};
}
inline constexpr float kNoCrossing = -1.f;  // MarchRay: the ray met no front face

// The walk of pixel (x, y)'s ray (`ray`: RayOfPixel) to the first zero crossing (front face)
// of the TSDF, skipping empty 4x4x4-brick groups and empty bricks: the crossing's distance
// along the ray, or kNoCrossing where the ray met nothing or a back face first. `last` (where
// given) is left with the brick of the walk's last step, which ShadeCrossing may use to spare
// look-ups.
template <typename Enc>
HDRF_HD float MarchRay(const VolumeView<Enc>& V, const RaycastArgs& a, int x, int y, const PixelRay& ray,
                       typename VolumeView<Enc>::BrickHint* last = nullptr) {
  const float vs = V.voxel_m, trunc = V.trunc_m, bs = vs * kBrick;
  const Float3 dc = ray.dc, dw = ray.dw, o = ray.o;
  // The volume has no bounds: the ray runs from near (or from where its tile's guide says the
  // surface can begin) to far, skipping empty space, and only where it crosses the box of the
  // allocated bricks (nothing outside it can be hit).
  float t0 = a.near_m;
  float t1 = a.far_m;
  if (a.start.data) {
    const float d = a.start(x / kGuideTile, y / kGuideTile) / dc.z;  // depth -> distance along the ray
    t0 = d > t0 ? d : t0;
  }
  const float inv_d[3] = {fabsf(dw.x) > 1e-9f ? 1.f / dw.x : 1e9f, fabsf(dw.y) > 1e-9f ? 1.f / dw.y : 1e9f,
                          fabsf(dw.z) > 1e-9f ? 1.f / dw.z : 1e9f};
  if (!ClipToBox(a, o, inv_d, &t0, &t1)) return kNoCrossing;
  // Distance along the ray to the exit of the grid cell (of side `cell`) holding p.
  auto cell_exit = [&](const Float3& p, float cell, float t) {
    const float gp[3] = {p.x / cell, p.y / cell, p.z / cell};
    float te = t1;
    for (int k = 0; k < 3; ++k) {
      if (inv_d[k] == 1e9f) continue;
      const float c = float(FloorToInt(gp[k]));
      const float edge = inv_d[k] > 0.f ? c + 1.f : c;
      const float tk = t + (edge - gp[k]) * cell * inv_d[k];
      te = te < tk ? te : tk;
    }
    return te;
  };
  float t = t0, prev_f = 1.f, prev_t = -1.f;
  bool prev_valid = false;
  typename VolumeView<Enc>::BrickHint hint;  // the brick of the last step (steps are shorter than a brick)
  while (t < t1) {
    const Float3 p = o + dw * t;
    const Float3 g = p / bs;
    if (!(fabsf(g.x) < float(kBrickRange - 1) && fabsf(g.y) < float(kBrickRange - 1) && fabsf(g.z) < float(kBrickRange - 1)))
      break;
    const int bx = FloorToInt(g.x), by = FloorToInt(g.y), bz = FloorToInt(g.z);
    // The brick first (one look-up where it is there, as near surfaces); where it is absent,
    // its group decides how far the ray may skip.
    if (!hint.valid || bx != hint.bx || by != hint.by || bz != hint.bz) {
      hint.bx = bx, hint.by = by, hint.bz = bz, hint.valid = true;
      hint.slot = V.bricks.Find(BrickKey(bx, by, bz));
    }
    if (hint.slot < 0) {
      const float cell = V.GroupAllocated(bx, by, bz) ? bs : 4 * bs;
      const float te = cell_exit(p, cell, t) + 0.01f * vs;
      t = t + 0.1f * vs > te ? t + 0.1f * vs : te;
      prev_valid = false;
      continue;
    }
    float f;
    if (!V.SampleTsdf(p, &f, hint)) {
      t += 0.5f * trunc;  // unobserved voxels inside an allocated brick
      prev_valid = false;
      continue;
    }
    if (prev_valid && prev_f > 0.f && f <= 0.f) {
      if (last) *last = hint;
      return prev_t + (t - prev_t) * prev_f / (prev_f - f);
    }
    if (prev_valid && prev_f < 0.f && f > 0.f) return kNoCrossing;  // back face: seen from behind
    prev_f = f;
    prev_t = t;
    prev_valid = true;
    // A sample at the truncation (f near 1) is at least the truncation distance in front of
    // any surface: the next may be a whole truncation on. Nearer, 0.8 of the distance.
    const float step = f > 0.99f ? trunc : 0.8f * f * trunc;
    t += 0.8f * vs > step ? 0.8f * vs : step;
  }
  return kNoCrossing;
}

// The hit at distance `ts` along `ray` (MarchRay's crossing): its point, the model's normal
// there, its depth in the camera, and the model's radiance and NR there; a zero hit where the
// normal is undefined. `near_hit`: a brick already looked up near the point (none:
// BrickHint{}); it spares look-ups only, the result is the same.
template <typename Enc>
HDRF_HD RayHit ShadeCrossing(const VolumeView<Enc>& V, const PixelRay& ray, float ts,
                             const typename VolumeView<Enc>::BrickHint& near_hit) {
  RayHit hit;
  const Float3 ps = ray.o + ray.dw * ts;
  Float3 nrm;
  // On the CPU the walk's last brick (near ps) spares look-ups, and the radiance is taken from
  // the cell's corners the normal found; the GPU keeps its registers (as the short way,
  // measured slower there).
#if defined(__CUDA_ARCH__)
  const typename VolumeView<Enc>::BrickHint hint{};
  const Enc** cell = nullptr;
  (void)near_hit;
#else
  const typename VolumeView<Enc>::BrickHint& hint = near_hit;
  const Enc* corners[8];
  const Enc** cell = corners;
#endif
  if (!V.Gradient(ps, &nrm, hint, cell)) return hit;
  hit.vertex = ps;
  hit.normal = nrm;
  hit.depth = ts * ray.dc.z;
  Float3 rad;
  float nrv;
  if (cell && cell[0] ? V.SampleRadianceOfCell(ps, cell, &rad, &nrv) : V.SampleRadiance(ps, &rad, &nrv, hint)) {
    hit.radiance = rad;
    hit.nr = nrv;
  }
  return hit;
}

// The first front-face hit of pixel (x, y)'s ray (MarchRay, then ShadeCrossing); a zero hit
// where the ray met nothing.
template <typename Enc>
HDRF_HD RayHit RaycastPixel(const VolumeView<Enc>& V, const RaycastArgs& a, int x, int y) {
  const PixelRay ray = RayOfPixel(a, x, y);
  typename VolumeView<Enc>::BrickHint last;
  const float ts = MarchRay(V, a, x, y, ray, &last);
  return ts >= 0.f ? ShadeCrossing(V, ray, ts, last) : RayHit{};
}

}  // namespace hdrf::volume
