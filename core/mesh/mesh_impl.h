// Per-cube and per-edge steps of surface extraction (marching tetrahedra), shared by the CPU
// mesher (mesh.cpp) and the CUDA one (mesh_cuda.cu). A vertex is named by the
// voxel edge it lies on (a 64-bit key), so both backends build the same mesh: vertices in
// key order, triangles in cube order (bricks in slot order, voxels in memory order).
#pragma once

#include <cstdint>

#include "common/host_device.h"
#include "common/vec.h"
#include "volume/volume_impl.h"

namespace hdrf::mesh {

// Voxel coordinates span [-kVoxelRange, kVoxelRange) (the volume's brick range), 19 bits each
// once offset.
inline constexpr int kVoxelRange = volume::kBrickRange * volume::kBrick;
HDRF_HD std::uint64_t VoxelId(const int v[3]) {
  return (std::uint64_t(unsigned(v[2] + kVoxelRange)) << 38) | (std::uint64_t(unsigned(v[1] + kVoxelRange)) << 19) |
         std::uint64_t(unsigned(v[0] + kVoxelRange));
}

// Edge between voxels a and b (neighbours, diagonals included): the lower voxel id (z, y, x
// order) times 27 plus the offset code (-1..1 per axis) to the other; below 2^62.
HDRF_HD std::uint64_t EdgeKey(const int a[3], const int b[3]) {
  const std::uint64_t ia = VoxelId(a), ib = VoxelId(b);
  const int* lo = ia < ib ? a : b;
  const int* hi = ia < ib ? b : a;
  const int code = (hi[0] - lo[0] + 1) + 3 * (hi[1] - lo[1] + 1) + 9 * (hi[2] - lo[2] + 1);
  return (ia < ib ? ia : ib) * 27u + std::uint64_t(code);
}
HDRF_HD void DecodeEdgeKey(std::uint64_t key, int lo[3], int hi[3]) {
  const int code = int(key % 27u);
  const std::uint64_t id = key / 27u;
  lo[0] = int(id & 0x7ffffu) - kVoxelRange;
  lo[1] = int((id >> 19) & 0x7ffffu) - kVoxelRange;
  lo[2] = int((id >> 38) & 0x7ffffu) - kVoxelRange;
  hi[0] = lo[0] + code % 3 - 1;
  hi[1] = lo[1] + (code / 3) % 3 - 1;
  hi[2] = lo[2] + code / 9 - 1;
}

inline constexpr int kMaxCubeTriangles = 12;

// Triangles (as edge keys, unoriented) of the cube whose lowest corner is voxel (x, y, z):
// the cube is split into six tetrahedra around its diagonal 0-7 (corners x + 2y + 4z); only
// cubes of eight observed voxels with both signs produce any. `step` > 1: a cube `step`
// voxels on a side (x, y, z multiples of it), on the coarser lattice of every step-th voxel;
// its edge keys name that lattice's points (EdgeVertex with the same step).
template <typename V>
HDRF_HD int CubeTriangles(const volume::VolumeView<V>& vol, int x, int y, int z,
                          std::uint64_t tri[kMaxCubeTriangles][3], int step = 1) {
  const int tets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  float f[8];
  int ix[8][3];  // corners on the lattice
  bool pos = false, neg = false;
  for (int k = 0; k < 8; ++k) {
    ix[k][0] = x / step + (k & 1);
    ix[k][1] = y / step + ((k >> 1) & 1);
    ix[k][2] = z / step + (k >> 2);
    const V* v = vol.Get(ix[k][0] * step, ix[k][1] * step, ix[k][2] * step);
    if (!v || v->W() <= 0.f) return 0;
    f[k] = v->Tsdf();
    if (f[k] < 0.f) neg = true;
    else pos = true;
  }
  if (!pos || !neg) return 0;
  int nt = 0;
  for (int t = 0; t < 6; ++t) {
    int in[4], out[4], ni = 0, no = 0;
    for (int j = 0; j < 4; ++j) {
      const int k = tets[t][j];
      if (f[k] < 0.f) in[ni++] = k;
      else out[no++] = k;
    }
    if (ni == 0 || no == 0) continue;
    auto key = [&](int a, int b) { return EdgeKey(ix[a], ix[b]); };
    if (ni == 1) {
      tri[nt][0] = key(in[0], out[0]);
      tri[nt][1] = key(in[0], out[1]);
      tri[nt][2] = key(in[0], out[2]);
      ++nt;
    } else if (no == 1) {
      tri[nt][0] = key(out[0], in[0]);
      tri[nt][1] = key(out[0], in[1]);
      tri[nt][2] = key(out[0], in[2]);
      ++nt;
    } else {  // 2-2: a quad
      const std::uint64_t a = key(in[0], out[0]), b = key(in[0], out[1]);
      const std::uint64_t c = key(in[1], out[1]), d = key(in[1], out[0]);
      tri[nt][0] = a;
      tri[nt][1] = b;
      tri[nt][2] = c;
      ++nt;
      tri[nt][0] = a;
      tri[nt][1] = c;
      tri[nt][2] = d;
      ++nt;
    }
  }
  return nt;
}

// The vertex on an edge: the zero crossing of the TSDF between the two voxel centres, the
// TSDF gradient as normal, and the radiance interpolated (or taken from the one end seen).
// `step`: the lattice the key names (CubeTriangles).
template <typename V>
HDRF_HD void EdgeVertex(const volume::VolumeView<V>& vol, std::uint64_t key, Float3* p, Float3* nrm, Float3* rad,
                        int step = 1) {
  int lo[3], hi[3];
  DecodeEdgeKey(key, lo, hi);
  for (int i = 0; i < 3; ++i) lo[i] *= step, hi[i] *= step;
  const volume::Voxel a = vol.Get(lo[0], lo[1], lo[2])->Decode();
  const volume::Voxel b = vol.Get(hi[0], hi[1], hi[2])->Decode();
  const float t = a.tsdf / (a.tsdf - b.tsdf);
  const float vs = vol.voxel_m;
  const Float3 pa = Float3{(float(lo[0]) + 0.5f) * vs, (float(lo[1]) + 0.5f) * vs, (float(lo[2]) + 0.5f) * vs};
  const Float3 pb = Float3{(float(hi[0]) + 0.5f) * vs, (float(hi[1]) + 0.5f) * vs, (float(hi[2]) + 0.5f) * vs};
  *p = pa + (pb - pa) * t;
  *nrm = {0, 0, 1};
  vol.Gradient(*p, nrm);
  if (a.wr > 0.f && b.wr > 0.f) *rad = a.radiance + (b.radiance - a.radiance) * t;
  else if (a.wr > 0.f) *rad = a.radiance;
  else if (b.wr > 0.f) *rad = b.radiance;
  else *rad = {0, 0, 0};
}

// Orders a triangle's corners so that its face normal agrees with the vertex normals.
HDRF_HD void OrientTriangle(const Float3* position, const Float3* normal, std::int32_t t[3]) {
  const Float3 gn = Cross(position[t[1]] - position[t[0]], position[t[2]] - position[t[0]]);
  const Float3 avg = normal[t[0]] + normal[t[1]] + normal[t[2]];
  if (Dot(gn, avg) < 0.f) {
    const std::int32_t s = t[1];
    t[1] = t[2];
    t[2] = s;
  }
}

}  // namespace hdrf::mesh
