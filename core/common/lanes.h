// Four floats or ints in one vector register (GCC's vector extensions), for host loops that
// take four pixels or voxels at once: each lane does the scalar code's operations in its
// order, so the lanes give the scalar code's bits (the GPU's too).
#pragma once

#include "common/camera.h"
#include "common/vec.h"

namespace hdrf {

using Lanes = float __attribute__((vector_size(4 * sizeof(float))));
using LaneInts = int __attribute__((vector_size(4 * sizeof(int))));

// RoundToInt (vec.h) of each lane: the nearest integer, halves away from zero; INT_MIN for NaN
// and magnitudes past the int range.
inline LaneInts RoundToIntLanes(Lanes x) {
  const LaneInts magnitude = (LaneInts)x & 0x7fffffff;
  const LaneInts fits = (Lanes)magnitude < 2147483520.f;  // false for NaN
  const Lanes zero = {0.f, 0.f, 0.f, 0.f};
  const LaneInts i = __builtin_convertvector(fits ? x : zero, LaneInts);  // toward zero
  const Lanes d = x - __builtin_convertvector(i, Lanes);                 // the exact fractional part
  const LaneInts r = i - (d >= 0.5f) + (d <= -0.5f);                      // (a true comparison is -1)
  return fits ? r : -2147483647 - 1;
}

// Four points, one coordinate a vector. Apply and Project as RigidTransform::Apply and
// PinholeCamera::Project (vec.h, camera.h), operation for operation.
struct Lanes3 {
  Lanes x, y, z;
  // Points p[0..3] (consecutive pixels of an image of Float3).
  static Lanes3 Load(const Float3* p) {
    return {Lanes{p[0].x, p[1].x, p[2].x, p[3].x}, Lanes{p[0].y, p[1].y, p[2].y, p[3].y},
            Lanes{p[0].z, p[1].z, p[2].z, p[3].z}};
  }
  Float3 operator[](int k) const { return {x[k], y[k], z[k]}; }
};
inline Lanes3 Apply(const RigidTransform& T, const Lanes3& p) {
  const float* r = T.r;
  return {r[0] * p.x + r[1] * p.y + r[2] * p.z + T.t.x, r[3] * p.x + r[4] * p.y + r[5] * p.z + T.t.y,
          r[6] * p.x + r[7] * p.y + r[8] * p.z + T.t.z};
}
// The pixel positions u, v of camera-frame points (z > 0 where they are used).
inline void Project(const PinholeCamera& c, const Lanes3& p, Lanes* u, Lanes* v) {
  const Lanes inv_z = 1.0f / p.z;
  *u = c.fx * p.x * inv_z + c.cx;
  *v = c.fy * p.y * inv_z + c.cy;
}

}  // namespace hdrf
