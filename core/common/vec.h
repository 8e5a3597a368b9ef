// Small fixed-size vectors for per-element code on host and device (Eigen stays on the
// host side of the API).
#pragma once

#include <cmath>

#include "common/host_device.h"

namespace hdrf {

struct Float2 {
  float x, y;
};
struct Float3 {
  float x, y, z;
};

HDRF_HD Float3 operator+(Float3 a, Float3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
HDRF_HD Float3 operator-(Float3 a, Float3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
HDRF_HD Float3 operator-(Float3 a) { return {-a.x, -a.y, -a.z}; }
HDRF_HD Float3 operator*(Float3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
HDRF_HD Float3 operator*(float s, Float3 a) { return {a.x * s, a.y * s, a.z * s}; }
HDRF_HD Float3 operator/(Float3 a, float s) { return a * (1.0f / s); }
HDRF_HD Float3 Mul(Float3 a, Float3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
HDRF_HD Float3& operator+=(Float3& a, Float3 b) { return a = a + b; }
HDRF_HD float Dot(Float3 a, Float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
HDRF_HD Float3 Cross(Float3 a, Float3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
HDRF_HD float Length(Float3 a) { return sqrtf(Dot(a, a)); }
// The nearest integer, halves away from zero: lroundf's result wherever it fits an int, but
// inline on the host too (lroundf is a library call there, a tenth of the integration's time).
// NaN and magnitudes past the int range give INT_MIN, which every caller's bounds test refuses.
HDRF_HD int RoundToInt(float x) {
  if (!(fabsf(x) < 2147483520.f)) return -2147483647 - 1;
  const int i = int(x);             // toward zero
  const float d = x - float(i);     // the exact fractional part
  return i + (d >= 0.5f ? 1 : 0) - (d <= -0.5f ? 1 : 0);
}
// floorf as an int for |x| < 2^31 (what int(floorf(x)) gives there): on the host without the
// library's floor, which x86-64's baseline instruction set has no instruction for (the ray
// cast takes three per trilinear sample).
HDRF_HD int FloorToInt(float x) {
#if defined(__CUDA_ARCH__)
  return int(floorf(x));
#else
  const int i = int(x);  // toward zero
  return i - (x < float(i) ? 1 : 0);
#endif
}
HDRF_HD Float3 Normalized(Float3 a) { return a * (1.0f / Length(a)); }
HDRF_HD float MaxComponent(Float3 a) { return fmaxf(a.x, fmaxf(a.y, a.z)); }
HDRF_HD float Luminance(Float3 rgb) {  // Rec. 709 / sRGB primaries
  return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

// Row-major 3x3 rotation and translation: a rigid transform usable in kernels.
struct RigidTransform {
  float r[9];
  Float3 t;
  HDRF_HD Float3 Apply(Float3 p) const {
    return {r[0] * p.x + r[1] * p.y + r[2] * p.z + t.x, r[3] * p.x + r[4] * p.y + r[5] * p.z + t.y,
            r[6] * p.x + r[7] * p.y + r[8] * p.z + t.z};
  }
  HDRF_HD Float3 Rotate(Float3 p) const {
    return {r[0] * p.x + r[1] * p.y + r[2] * p.z, r[3] * p.x + r[4] * p.y + r[5] * p.z,
            r[6] * p.x + r[7] * p.y + r[8] * p.z};
  }
};

}  // namespace hdrf
