// Per-voxel and per-ray steps of the volume, shared by the CPU loops (volume.cpp) and the
// CUDA kernels (volume_cuda.cu): sampling, integration of one voxel, brick marking along
// one depth ray, and ray casting of one pixel.
#pragma once

#include <cstdint>

#include "common/camera.h"
#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"

namespace hdrf::volume {

struct Voxel {
  float tsdf = 1;                 // signed distance / truncation, in [-1, 1]
  float w = 0;                    // TSDF weight
  Float3 radiance{0, 0, 0};       // HDR radiance, model units
  float nr = 0;                   // normalized radiance
  float wr = 0;                   // radiance weight
};

inline constexpr int kBrick = 8;

// The volume's arrays and geometry, wherever they live.
struct VolumeView {
  const int* index = nullptr;            // nb^3 brick slots, -1 = unallocated
  const std::uint8_t* coarse = nullptr;  // nc^3: any brick allocated in this 4x4x4 group
  Voxel* pool = nullptr;                 // 512 voxels per allocated brick
  int n = 0, nb = 0, nc = 0;             // voxels, bricks and coarse cells per side
  Float3 origin{0, 0, 0};                // world position of voxel (0,0,0)'s corner
  float voxel_m = 0, size_m = 0, trunc_m = 0;

  HDRF_HD int BrickIndex(int bx, int by, int bz) const { return (bz * nb + by) * nb + bx; }
  HDRF_HD bool BrickAllocated(int bx, int by, int bz) const {
    return bx >= 0 && by >= 0 && bz >= 0 && bx < nb && by < nb && bz < nb && index[BrickIndex(bx, by, bz)] >= 0;
  }
  HDRF_HD const Voxel* Get(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= n || y >= n || z >= n) return nullptr;
    const int b = index[BrickIndex(x >> 3, y >> 3, z >> 3)];
    return b < 0 ? nullptr : &pool[long(b) * 512 + ((z & 7) * 8 + (y & 7)) * 8 + (x & 7)];
  }
  // Voxel-centre grid coordinates of a world point.
  HDRF_HD Float3 Grid(Float3 p) const { return (p - origin) * (1.f / voxel_m) - Float3{0.5f, 0.5f, 0.5f}; }

  // Trilinear TSDF over the observed corners, renormalised; undefined (false) when the
  // observed corners carry less than half of the interpolation weight.
  HDRF_HD bool SampleTsdf(Float3 p, float* out) const {
    const Float3 g = Grid(p);
    const int x = int(floorf(g.x)), y = int(floorf(g.y)), z = int(floorf(g.z));
    const float ax = g.x - float(x), ay = g.y - float(y), az = g.z - float(z);
    float acc = 0.f, wsum = 0.f;
    if ((x & 7) != 7 && (y & 7) != 7 && (z & 7) != 7 && x >= 0 && y >= 0 && z >= 0 && x < n - 1 &&
        y < n - 1 && z < n - 1) {
      // Fast path: all eight corners in one brick.
      const int b = index[BrickIndex(x >> 3, y >> 3, z >> 3)];
      if (b < 0) return false;
      const Voxel* base = &pool[long(b) * 512 + ((z & 7) * 8 + (y & 7)) * 8 + (x & 7)];
      for (int k = 0; k < 8; ++k) {
        const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
        const Voxel& v = base[dz * 64 + dy * 8 + dx];
        if (v.w <= 0.f) continue;
        const float w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) * (dz ? az : 1 - az);
        acc += w * v.tsdf;
        wsum += w;
      }
    } else {
      for (int k = 0; k < 8; ++k) {
        const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
        const Voxel* v = Get(x + dx, y + dy, z + dz);
        if (!v || v->w <= 0.f) continue;
        const float w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) * (dz ? az : 1 - az);
        acc += w * v->tsdf;
        wsum += w;
      }
    }
    if (wsum < 0.5f) return false;
    *out = acc / wsum;
    return true;
  }

  // Trilinear radiance and NR over the corners with radiance weight; false if none has any.
  HDRF_HD bool SampleRadiance(Float3 p, Float3* rad, float* nr) const {
    const Float3 g = Grid(p);
    const int x = int(floorf(g.x)), y = int(floorf(g.y)), z = int(floorf(g.z));
    const float ax = g.x - float(x), ay = g.y - float(y), az = g.z - float(z);
    Float3 r{0, 0, 0};
    float nn = 0.f, wsum = 0.f;
    for (int k = 0; k < 8; ++k) {
      const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
      const Voxel* v = Get(x + dx, y + dy, z + dz);
      if (!v || v->wr <= 0.f) continue;
      const float w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) * (dz ? az : 1 - az);
      r += v->radiance * w;
      nn += v->nr * w;
      wsum += w;
    }
    if (wsum < 1e-3f) return false;
    *rad = r / wsum;
    *nr = nn / wsum;
    return true;
  }

  // Normal from the TSDF gradient (central differences one voxel apart).
  HDRF_HD bool Gradient(Float3 p, Float3* nrm) const {
    const float h = voxel_m;
    float fx0, fx1, fy0, fy1, fz0, fz1;
    if (!SampleTsdf(p - Float3{h, 0, 0}, &fx0) || !SampleTsdf(p + Float3{h, 0, 0}, &fx1) ||
        !SampleTsdf(p - Float3{0, h, 0}, &fy0) || !SampleTsdf(p + Float3{0, h, 0}, &fy1) ||
        !SampleTsdf(p - Float3{0, 0, h}, &fz0) || !SampleTsdf(p + Float3{0, 0, h}, &fz1))
      return false;
    const Float3 g{fx1 - fx0, fy1 - fy0, fz1 - fz0};
    const float len = Length(g);
    if (len < 1e-6f) return false;
    *nrm = g / len;
    return true;
  }
};

// ---- Integration ------------------------------------------------------------------------------
struct IntegrateArgs {
  ImageView<const float> depth;
  ImageView<const Float3> normals;         // camera frame, for w_F = |n.v|
  ImageView<const Float3> radiance;        // model units; data == nullptr: depth only
  ImageView<const float> nr, confidence, max_confidence;
  float radiance_scale = 1;                // exposure compensation applied on the fly
  PinholeCamera cam;
  RigidTransform T_camera_world;
  Float3 origin;
  float voxel_m, trunc_m, max_weight, max_radiance_weight, tau0, cos_tau1;
};

// Brick coordinates along the depth ray of pixel (x, y) within the truncation band; calls
// mark(bx, by, bz) for each (a brick may be named more than once).
template <typename Mark>
HDRF_HD void ForBricksAlongRay(const IntegrateArgs& a, const RigidTransform& T_world_camera, int nb,
                               int x, int y, Mark&& mark) {
  const float z = a.depth(x, y);
  if (!(z > 0.f)) return;
  const float bs = a.voxel_m * kBrick;
  const Float3 pc = a.cam.BackProject(float(x), float(y), z);
  const float len = Length(pc);
  const Float3 dir = pc / len;
  for (float d = len - a.trunc_m; d <= len + a.trunc_m; d += 0.5f * bs) {
    const Float3 pw = T_world_camera.Apply(dir * d);
    const Float3 g = (pw - a.origin) / bs;
    const int bx = int(floorf(g.x)), by = int(floorf(g.y)), bz = int(floorf(g.z));
    if (bx < 0 || by < 0 || bz < 0 || bx >= nb || by >= nb || bz >= nb) continue;
    mark(bx, by, bz);
  }
}

// Updates voxel i (0..511) of the brick at brick coordinates (bx, by, bz). Returns bit 0:
// TSDF updated, bit 1: radiance updated.
HDRF_HD int IntegrateVoxel(const IntegrateArgs& a, int bx, int by, int bz, int i, Voxel& vx) {
  const int lx = i & 7, ly = (i >> 3) & 7, lz = i >> 6;
  const float vs = a.voxel_m, trunc = a.trunc_m;
  const Float3 pw = a.origin + Float3{(float(bx * 8 + lx) + 0.5f) * vs, (float(by * 8 + ly) + 0.5f) * vs,
                                      (float(bz * 8 + lz) + 0.5f) * vs};
  const Float3 pc = a.T_camera_world.Apply(pw);
  if (pc.z <= 0.05f) return 0;
  const Float2 px = a.cam.Project(pc);
  const int u = int(lroundf(px.x)), v = int(lroundf(px.y));
  if (u < 0 || v < 0 || u >= a.cam.width || v >= a.cam.height) return 0;
  const float zd = a.depth(u, v);
  if (!(zd > 0.f)) return 0;
  const float sdf = zd - pc.z;
  if (sdf < -trunc) return 0;
  const float f = sdf / trunc < 1.f ? sdf / trunc : 1.f;
  const Float3 ray = Normalized(pc);
  const Float3 nrm = a.normals(u, v);
  const float cosv = fabsf(Dot(nrm, ray));
  const float wf = Length(nrm) > 0.f ? (cosv > 0.05f ? cosv : 0.05f) : 0.05f;
  vx.tsdf = (vx.w * vx.tsdf + wf * f) / (vx.w + wf);
  vx.w = vx.w + wf < a.max_weight ? vx.w + wf : a.max_weight;
  int done = 1;
  if (fabsf(sdf) < trunc && a.radiance.data && a.max_confidence(u, v) > a.tau0 && cosv >= a.cos_tau1) {
    const float wr = a.confidence(u, v);
    if (wr > 0.f) {
      const Float3 live = a.radiance(u, v) * a.radiance_scale;
      vx.radiance = (vx.radiance * vx.wr + live * wr) / (vx.wr + wr);
      vx.nr = (vx.nr * vx.wr + a.nr(u, v) * wr) / (vx.wr + wr);
      vx.wr = vx.wr + wr < a.max_radiance_weight ? vx.wr + wr : a.max_radiance_weight;
      done |= 2;
    }
  }
  return done;
}

// ---- Ray casting ------------------------------------------------------------------------------
struct RaycastArgs {
  PinholeCamera cam;
  RigidTransform T_world_camera;
  float near_m, far_m;
};
struct RayHit {
  Float3 vertex{0, 0, 0}, normal{0, 0, 0}, radiance{0, 0, 0};
  float nr = 0, depth = 0;
};

// The first zero crossing (front face) of the TSDF along the ray of pixel (x, y), skipping
// empty 4x4x4-brick groups and empty bricks; a zero hit where the ray met nothing.
HDRF_HD RayHit RaycastPixel(const VolumeView& V, const RaycastArgs& a, int x, int y) {
  RayHit hit;
  const float vs = V.voxel_m, trunc = V.trunc_m, bs = vs * kBrick;
  const Float3 dc = Normalized(a.cam.BackProject(float(x), float(y), 1.f));
  const Float3 dw = a.T_world_camera.Rotate(dc), o = a.T_world_camera.t;
  // Clip the ray to the volume's cube.
  float t0 = a.near_m, t1 = a.far_m;
  const float ov[3] = {o.x, o.y, o.z}, dv[3] = {dw.x, dw.y, dw.z};
  const float lo[3] = {V.origin.x, V.origin.y, V.origin.z};
  for (int k = 0; k < 3; ++k) {
    if (fabsf(dv[k]) < 1e-9f) continue;
    float ta = (lo[k] - ov[k]) / dv[k], tb = (lo[k] + V.size_m - ov[k]) / dv[k];
    if (ta > tb) {
      const float s = ta;
      ta = tb;
      tb = s;
    }
    t0 = t0 > ta ? t0 : ta;
    t1 = t1 < tb ? t1 : tb;
  }
  const float inv_d[3] = {fabsf(dw.x) > 1e-9f ? 1.f / dw.x : 1e9f, fabsf(dw.y) > 1e-9f ? 1.f / dw.y : 1e9f,
                          fabsf(dw.z) > 1e-9f ? 1.f / dw.z : 1e9f};
  // Distance along the ray to the exit of the grid cell (of side `cell`) holding p.
  auto cell_exit = [&](const Float3& p, float cell, float t) {
    const float gp[3] = {(p.x - V.origin.x) / cell, (p.y - V.origin.y) / cell, (p.z - V.origin.z) / cell};
    float te = t1;
    for (int k = 0; k < 3; ++k) {
      if (inv_d[k] == 1e9f) continue;
      const float c = floorf(gp[k]);
      const float edge = inv_d[k] > 0.f ? c + 1.f : c;
      const float tk = t + (edge - gp[k]) * cell * inv_d[k];
      te = te < tk ? te : tk;
    }
    return te;
  };
  float t = t0, prev_f = 1.f, prev_t = -1.f;
  bool prev_valid = false;
  while (t < t1) {
    const Float3 p = o + dw * t;
    const Float3 g = (p - V.origin) / bs;
    const int bx = int(floorf(g.x)), by = int(floorf(g.y)), bz = int(floorf(g.z));
    if (bx < 0 || by < 0 || bz < 0 || bx >= V.nb || by >= V.nb || bz >= V.nb) break;
    if (!V.coarse[((bz >> 2) * V.nc + (by >> 2)) * V.nc + (bx >> 2)]) {
      const float te = cell_exit(p, 4 * bs, t) + 0.01f * vs;
      t = t + 0.1f * vs > te ? t + 0.1f * vs : te;
      prev_valid = false;
      continue;
    }
    if (!V.BrickAllocated(bx, by, bz)) {
      const float te = cell_exit(p, bs, t) + 0.01f * vs;
      t = t + 0.1f * vs > te ? t + 0.1f * vs : te;
      prev_valid = false;
      continue;
    }
    float f;
    if (!V.SampleTsdf(p, &f)) {
      t += 0.5f * trunc;  // unobserved voxels inside an allocated brick
      prev_valid = false;
      continue;
    }
    if (prev_valid && prev_f > 0.f && f <= 0.f) {
      const float ts = prev_t + (t - prev_t) * prev_f / (prev_f - f);
      const Float3 ps = o + dw * ts;
      Float3 nrm;
      if (V.Gradient(ps, &nrm)) {
        hit.vertex = ps;
        hit.normal = nrm;
        hit.depth = ts * dc.z;
        Float3 rad;
        float nrv;
        if (V.SampleRadiance(ps, &rad, &nrv)) {
          hit.radiance = rad;
          hit.nr = nrv;
        }
      }
      return hit;
    }
    if (prev_valid && prev_f < 0.f && f > 0.f) return hit;  // back face: seen from behind
    prev_f = f;
    prev_t = t;
    prev_valid = true;
    const float step = 0.8f * f * trunc;
    t += 0.8f * vs > step ? 0.8f * vs : step;
  }
  return hit;
}

}  // namespace hdrf::volume
