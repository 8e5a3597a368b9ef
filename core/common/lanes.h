// Four floats or ints in one vector register (GCC's vector extensions), for host loops that
// take four pixels or voxels at once: each lane does the scalar code's operations in its
// order, so the lanes give the scalar code's bits (the GPU's too).
#pragma once

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

}  // namespace hdrf
