#include "volume/volume.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace hdrf::volume {

void VolumeOptions::Check() const {
  if (resolution < 8 || resolution % 8 != 0)
    throw SettingError("--volume-res", "must be a positive multiple of 8, got " + std::to_string(resolution));
  if (resolution > 4096)
    throw SettingError("--volume-res", std::to_string(resolution) + " is more than 4096 voxels per side");
  if (!(size_m > 0) || !std::isfinite(size_m))
    throw SettingError("--volume-size", "must be a positive number of metres");
  if (!(truncation_voxels >= 1)) throw SettingError("truncation_voxels", "must be >= 1");
  if (!(max_weight > 0) || !(max_radiance_weight > 0)) throw SettingError("max_weight", "must be > 0");
  if (!(tau1_deg > 0 && tau1_deg <= 90)) throw SettingError("--tau1", "must be in (0, 90] degrees");
  if (!(tau0 >= 0 && tau0 < 1)) throw SettingError("--tau0", "must be in [0, 1)");
  const double nb = resolution / 8.0;
  const double index_mb = nb * nb * nb * 4.0 / (1024.0 * 1024.0);
  const double brick_mb = 512.0 * sizeof(Voxel) / (1024.0 * 1024.0);
  if (index_mb + 64 * brick_mb > max_memory_mb)
    throw SettingError("--volume-res", "a " + std::to_string(resolution) + "^3 volume needs " +
                                           std::to_string(int(index_mb)) + " MiB for its brick index alone, more than the " +
                                           std::to_string(int(max_memory_mb)) + " MiB allowed (max_memory_mb)");
}

Volume::Volume(const VolumeOptions& o) : o_(o) {
  o_.Check();
  n_ = o_.resolution;
  nb_ = n_ / kBrick;
  const float half = 0.5f * o_.size_m;
  origin_ = {-half, -half, -half};
  index_.assign(std::size_t(nb_) * nb_ * nb_, -1);
  nc_ = (nb_ + 3) / 4;
  coarse_.assign(std::size_t(nc_) * nc_ * nc_, 0);
  const double brick_bytes = 512.0 * sizeof(Voxel);
  max_bricks_ = std::size_t(std::max(0.0, (o_.max_memory_mb * 1024 * 1024 - double(index_.size()) * 4) / brick_bytes));
}

std::size_t Volume::bytes() const {
  return index_.size() * sizeof(int) + pool_.size() * sizeof(Voxel);
}

Voxel* Volume::Allocate(int bx, int by, int bz) {
  int& slot = index_[BrickIndex(bx, by, bz)];
  if (slot >= 0) return MutableBrick(slot);
  if (brick_coord_.size() >= max_bricks_) {
    full_ = true;
    return nullptr;
  }
  slot = int(brick_coord_.size());
  brick_coord_.push_back({bx, by, bz});
  coarse_[std::size_t(((bz >> 2) * nc_ + (by >> 2)) * nc_ + (bx >> 2))] = 1;
  pool_.resize(pool_.size() + 512);
  return MutableBrick(slot);
}

namespace {
// Voxel-centre grid coordinates of a world point.
inline Float3 Grid(Float3 p, Float3 origin, float inv_vs) { return (p - origin) * inv_vs - Float3{0.5f, 0.5f, 0.5f}; }
}  // namespace

bool Volume::SampleTsdf(Float3 p, float* out) const {
  // Trilinear over the observed corners, renormalised; undefined when the observed corners
  // carry less than half of the interpolation weight (far from anything seen).
  const Float3 g = Grid(p, origin_, 1.f / o_.voxel_m());
  const int x = int(std::floor(g.x)), y = int(std::floor(g.y)), z = int(std::floor(g.z));
  const float ax = g.x - x, ay = g.y - y, az = g.z - z;
  float acc = 0, wsum = 0;
  if ((x & 7) != 7 && (y & 7) != 7 && (z & 7) != 7 && x >= 0 && y >= 0 && z >= 0 && x < n_ - 1 &&
      y < n_ - 1 && z < n_ - 1) {
    // Fast path: all eight corners in one brick.
    const int b = index_[std::size_t(BrickIndex(x >> 3, y >> 3, z >> 3))];
    if (b < 0) return false;
    const Voxel* base = &pool_[std::size_t(b) * 512 + std::size_t(((z & 7) * 8 + (y & 7)) * 8 + (x & 7))];
    for (int k = 0; k < 8; ++k) {
      const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
      const Voxel& v = base[dz * 64 + dy * 8 + dx];
      if (v.w <= 0) continue;
      const float w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) * (dz ? az : 1 - az);
      acc += w * v.tsdf;
      wsum += w;
    }
  } else {
    for (int k = 0; k < 8; ++k) {
      const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
      const Voxel* v = Get(x + dx, y + dy, z + dz);
      if (!v || v->w <= 0) continue;
      const float w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) * (dz ? az : 1 - az);
      acc += w * v->tsdf;
      wsum += w;
    }
  }
  if (wsum < 0.5f) return false;
  *out = acc / wsum;
  return true;
}

bool Volume::SampleRadiance(Float3 p, Float3* rad, float* nr) const {
  const Float3 g = Grid(p, origin_, 1.f / o_.voxel_m());
  const int x = int(std::floor(g.x)), y = int(std::floor(g.y)), z = int(std::floor(g.z));
  const float ax = g.x - x, ay = g.y - y, az = g.z - z;
  Float3 r{0, 0, 0};
  float n = 0, wsum = 0;
  for (int k = 0; k < 8; ++k) {
    const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
    const Voxel* v = Get(x + dx, y + dy, z + dz);
    if (!v || v->wr <= 0) continue;
    const float w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) * (dz ? az : 1 - az);
    r += v->radiance * w;
    n += v->nr * w;
    wsum += w;
  }
  if (wsum < 1e-3f) return false;
  *rad = r / wsum;
  *nr = n / wsum;
  return true;
}

bool Volume::Gradient(Float3 p, Float3* n) const {
  const float h = o_.voxel_m();
  float fx0, fx1, fy0, fy1, fz0, fz1;
  if (!SampleTsdf(p - Float3{h, 0, 0}, &fx0) || !SampleTsdf(p + Float3{h, 0, 0}, &fx1) ||
      !SampleTsdf(p - Float3{0, h, 0}, &fy0) || !SampleTsdf(p + Float3{0, h, 0}, &fy1) ||
      !SampleTsdf(p - Float3{0, 0, h}, &fz0) || !SampleTsdf(p + Float3{0, 0, h}, &fz1))
    return false;
  const Float3 g{fx1 - fx0, fy1 - fy0, fz1 - fz0};
  const float len = Length(g);
  if (len < 1e-6f) return false;
  *n = g / len;
  return true;
}

Volume::IntegrateStats Volume::Integrate(const FrameInput& in) {
  IntegrateStats st;
  const DepthImage& depth = *in.depth_m;
  const PinholeCamera& cam = in.camera;
  const RigidTransform T = ToRigidTransform(in.T_world_camera);
  const RigidTransform Tinv = ToRigidTransform(in.T_world_camera.inverse());
  const float vs = o_.voxel_m(), trunc = o_.truncation_m(), bs = vs * kBrick;
  // 1. Bricks within the truncation band of every depth sample (every 2nd pixel).
  std::vector<std::uint8_t> visible(index_.size(), 0);
  for (int y = 0; y < depth.height(); y += 2)
    for (int x = 0; x < depth.width(); x += 2) {
      const float z = depth(x, y);
      if (!(z > 0)) continue;
      const Float3 pc = cam.BackProject(float(x), float(y), z);
      const float len = Length(pc);
      const Float3 dir = pc / len;
      for (float d = len - trunc; d <= len + trunc; d += 0.5f * bs) {
        const Float3 pw = T.Apply(dir * d);
        const Float3 g = (pw - origin_) / bs;
        const int bx = int(std::floor(g.x)), by = int(std::floor(g.y)), bz = int(std::floor(g.z));
        if (bx < 0 || by < 0 || bz < 0 || bx >= nb_ || by >= nb_ || bz >= nb_) continue;
        visible[std::size_t(BrickIndex(bx, by, bz))] = 1;
      }
    }
  std::vector<int> todo;
  for (int bz = 0; bz < nb_; ++bz)
    for (int by = 0; by < nb_; ++by)
      for (int bx = 0; bx < nb_; ++bx) {
        const int i = BrickIndex(bx, by, bz);
        if (!visible[std::size_t(i)]) continue;
        const bool existed = index_[std::size_t(i)] >= 0;
        if (!Allocate(bx, by, bz)) continue;
        st.new_bricks += !existed;
        todo.push_back(index_[std::size_t(i)]);
      }
  st.visible_bricks = todo.size();
  // 2. Update the voxels of those bricks.
  const float cos_tau1 = std::cos(o_.tau1_deg * 3.14159265f / 180.f);
  std::size_t updated = 0, rad_updates = 0;
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : updated, rad_updates)
  for (long k = 0; k < long(todo.size()); ++k) {
    const int b = todo[std::size_t(k)];
    const auto bc = brick_coord_[std::size_t(b)];
    Voxel* vox = MutableBrick(b);
    for (int i = 0; i < 512; ++i) {
      const int lx = i & 7, ly = (i >> 3) & 7, lz = i >> 6;
      const Float3 pw = origin_ + Float3{(bc[0] * 8 + lx + 0.5f) * vs, (bc[1] * 8 + ly + 0.5f) * vs,
                                         (bc[2] * 8 + lz + 0.5f) * vs};
      const Float3 pc = Tinv.Apply(pw);
      if (pc.z <= 0.05f) continue;
      const Float2 px = cam.Project(pc);
      const int u = int(std::lround(px.x)), v = int(std::lround(px.y));
      if (u < 0 || v < 0 || u >= cam.width || v >= cam.height) continue;
      const float zd = depth(u, v);
      if (!(zd > 0)) continue;
      const float sdf = zd - pc.z;
      if (sdf < -trunc) continue;
      const float f = std::min(1.f, sdf / trunc);
      const Float3 ray = Normalized(pc);
      const Float3 nrm = (*in.normals)(u, v);
      const float cosv = std::abs(Dot(nrm, ray));
      const float wf = Length(nrm) > 0 ? std::max(cosv, 0.05f) : 0.05f;
      Voxel& vx = vox[i];
      vx.tsdf = (vx.w * vx.tsdf + wf * f) / (vx.w + wf);
      vx.w = std::min(vx.w + wf, o_.max_weight);
      ++updated;
      if (std::abs(sdf) < trunc && in.radiance && (*in.max_confidence)(u, v) > o_.tau0 &&
          cosv >= cos_tau1) {
        const float wr = (*in.confidence)(u, v);
        if (wr > 0) {
          vx.radiance = (vx.radiance * vx.wr + (*in.radiance)(u, v) * wr) / (vx.wr + wr);
          vx.nr = (vx.nr * vx.wr + (*in.nr)(u, v) * wr) / (vx.wr + wr);
          vx.wr = std::min(vx.wr + wr, o_.max_radiance_weight);
          ++rad_updates;
        }
      }
    }
  }
  st.voxels_updated = updated;
  st.radiance_updates = rad_updates;
  return st;
}

Volume::Rendering Volume::Raycast(const PinholeCamera& cam, const Pose& T_wc, float near_m,
                                  float far_m) const {
  Rendering r;
  const int w = cam.width, h = cam.height;
  r.vertex = Image<Float3>(w, h, Float3{0, 0, 0});
  r.normal = Image<Float3>(w, h, Float3{0, 0, 0});
  r.radiance = RadianceImage(w, h, Float3{0, 0, 0});
  r.nr = Image<float>(w, h, 0.f);
  r.depth = DepthImage(w, h, 0.f);
  const RigidTransform T = ToRigidTransform(T_wc);
  const float vs = o_.voxel_m(), trunc = o_.truncation_m(), bs = vs * kBrick;
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Float3 dc = Normalized(cam.BackProject(float(x), float(y), 1.f));
      const Float3 dw = T.Rotate(dc), o = T.t;
      // Clip the ray to the volume's cube.
      float t0 = near_m, t1 = far_m;
      {
        const float ov[3] = {o.x, o.y, o.z}, dv[3] = {dw.x, dw.y, dw.z};
        const float lo[3] = {origin_.x, origin_.y, origin_.z};
        for (int a = 0; a < 3; ++a) {
          if (std::abs(dv[a]) < 1e-9f) continue;
          float ta = (lo[a] - ov[a]) / dv[a], tb = (lo[a] + o_.size_m - ov[a]) / dv[a];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
        }
      }
      const float inv_d[3] = {std::abs(dw.x) > 1e-9f ? 1.f / dw.x : 1e9f,
                              std::abs(dw.y) > 1e-9f ? 1.f / dw.y : 1e9f,
                              std::abs(dw.z) > 1e-9f ? 1.f / dw.z : 1e9f};
      // Distance along the ray to the exit of the grid cell (of side `cell`) holding p.
      auto cell_exit = [&](const Float3& p, float cell, float t) {
        const float gp[3] = {(p.x - origin_.x) / cell, (p.y - origin_.y) / cell, (p.z - origin_.z) / cell};
        float te = t1;
        for (int a = 0; a < 3; ++a) {
          if (inv_d[a] == 1e9f) continue;
          const float c = std::floor(gp[a]);
          const float edge = inv_d[a] > 0 ? c + 1.f : c;
          te = std::min(te, t + (edge - gp[a]) * cell * inv_d[a]);
        }
        return te;
      };
      float t = t0, prev_f = 1, prev_t = -1;
      bool prev_valid = false;
      while (t < t1) {
        const Float3 p = o + dw * t;
        const Float3 g = (p - origin_) / bs;
        const int bx = int(std::floor(g.x)), by = int(std::floor(g.y)), bz = int(std::floor(g.z));
        const int cx = bx >> 2, cy = by >> 2, cz = bz >> 2;
        if (bx < 0 || by < 0 || bz < 0 || bx >= nb_ || by >= nb_ || bz >= nb_) break;
        if (!coarse_[std::size_t((cz * nc_ + cy) * nc_ + cx)]) {
          t = std::max(t + 0.1f * vs, cell_exit(p, 4 * bs, t) + 0.01f * vs);
          prev_valid = false;
          continue;
        }
        if (!BrickAllocated(bx, by, bz)) {
          t = std::max(t + 0.1f * vs, cell_exit(p, bs, t) + 0.01f * vs);
          prev_valid = false;
          continue;
        }
        float f;
        if (!SampleTsdf(p, &f)) {
          t += 0.5f * trunc;  // unobserved voxels inside an allocated brick
          prev_valid = false;
          continue;
        }
        if (prev_valid && prev_f > 0 && f <= 0) {
          const float ts = prev_t + (t - prev_t) * prev_f / (prev_f - f);
          const Float3 ps = o + dw * ts;
          Float3 n;
          if (Gradient(ps, &n)) {
            r.vertex(x, y) = ps;
            r.normal(x, y) = n;
            r.depth(x, y) = ts * dc.z;
            Float3 rad;
            float nrv;
            if (SampleRadiance(ps, &rad, &nrv)) {
              r.radiance(x, y) = rad;
              r.nr(x, y) = nrv;
            }
          }
          break;
        }
        if (prev_valid && prev_f < 0 && f > 0) break;  // back face: seen from behind
        prev_f = f;
        prev_t = t;
        prev_valid = true;
        t += std::max(0.8f * vs, 0.8f * f * trunc);
      }
    }
  return r;
}

}  // namespace hdrf::volume
