// The CPU integration's first pass over a brick (volume.cpp): ProjectVoxel for its 512 voxels,
// four at a time. Host only.
#pragma once

#include <cstdint>

#include "common/lanes.h"
#include "volume/volume_impl.h"

namespace hdrf::volume {

// ProjectVoxel for each of a brick's 512 voxels, in voxel order: those in view go to seen[],
// their numbers to at[]; returns how many. Four voxels of a row go at once (lanes.h), each
// lane with ProjectVoxel's operations in its order: the same bits.
inline int ProjectBrick(const IntegrateArgs& a, int bx, int by, int bz, VoxelInView* seen, std::int16_t* at) {
  const float vs = a.voxel_m, trunc = a.trunc_m;
  const PinholeCamera& cam = a.cam;
  int n = 0;
  for (int lz = 0; lz < 8; ++lz)
    for (int ly = 0; ly < 8; ++ly) {
      const float wy = (float(by * 8 + ly) + 0.5f) * vs, wz = (float(bz * 8 + lz) + 0.5f) * vs;
      for (int x0 = 0; x0 < 8; x0 += 4) {
        const int gx = bx * 8 + x0;
        const LaneInts ix = {gx, gx + 1, gx + 2, gx + 3};
        const Lanes wx = (__builtin_convertvector(ix, Lanes) + 0.5f) * vs;
        const Lanes3 pc = Apply(a.T_camera_world, Lanes3{wx, Lanes{wy, wy, wy, wy}, Lanes{wz, wz, wz, wz}});
        const LaneInts front = pc.z > 0.05f;  // (ProjectVoxel: not <= 0.05)
        if (!(front[0] | front[1] | front[2] | front[3])) continue;
        Lanes fu, fv;
        Project(cam, pc, &fu, &fv);
        const LaneInts u = RoundToIntLanes(fu), v = RoundToIntLanes(fv);
        for (int k = 0; k < 4; ++k) {
          if (!front[k] || u[k] < 0 || v[k] < 0 || u[k] >= cam.width || v[k] >= cam.height) continue;
          const float zd = a.depth(u[k], v[k]);
          if (!(zd > 0.f)) continue;
          const float sdf = zd - pc.z[k];
          if (sdf < -trunc) continue;
          seen[n] = {pc[k], u[k], v[k], sdf};
          at[n++] = std::int16_t(lz * 64 + ly * 8 + x0 + k);
        }
      }
    }
  return n;
}

}  // namespace hdrf::volume
