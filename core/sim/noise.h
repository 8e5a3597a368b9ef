// Deterministic hashing, value noise and Gaussian samples: the same numbers for a seed on
// any machine and any number of threads.
#pragma once

#include <cmath>
#include <cstdint>

#include "common/vec.h"

namespace hdrf::sim {

inline std::uint32_t Hash32(std::uint32_t x) {  // lowbias32 (public-domain integer hash)
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

inline std::uint32_t Hash(std::uint32_t a, std::uint32_t b) { return Hash32(a ^ Hash32(b)); }
inline std::uint32_t Hash(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  return Hash32(a ^ Hash32(b ^ Hash32(c)));
}

// Uniform in [0, 1).
inline float HashToUnit(std::uint32_t h) { return float(Hash32(h) >> 8) * (1.0f / 16777216.0f); }

// Standard normal sample from two hash streams (Box-Muller).
inline float Gaussian(std::uint32_t h) {
  const float u1 = (float(Hash32(h) >> 8) + 0.5f) * (1.0f / 16777216.0f);
  const float u2 = float(Hash32(h ^ 0x9e3779b9U) >> 8) * (1.0f / 16777216.0f);
  return std::sqrt(-2.0f * std::log(u1)) * std::cos(6.28318530718f * u2);
}

// Smooth 3-D value noise in [0, 1], three octaves.
inline float ValueNoise(Float3 p, std::uint32_t seed) {
  const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int ix = int(fx), iy = int(fy), iz = int(fz);
  auto smooth = [](float t) { return t * t * (3 - 2 * t); };
  const float tx = smooth(p.x - fx), ty = smooth(p.y - fy), tz = smooth(p.z - fz);
  auto corner = [&](int dx, int dy, int dz) {
    return HashToUnit(Hash(std::uint32_t(ix + dx) * 73856093u ^ std::uint32_t(iy + dy) * 19349663u,
                           std::uint32_t(iz + dz) * 83492791u, seed));
  };
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  const float x00 = lerp(corner(0, 0, 0), corner(1, 0, 0), tx);
  const float x10 = lerp(corner(0, 1, 0), corner(1, 1, 0), tx);
  const float x01 = lerp(corner(0, 0, 1), corner(1, 0, 1), tx);
  const float x11 = lerp(corner(0, 1, 1), corner(1, 1, 1), tx);
  return lerp(lerp(x00, x10, ty), lerp(x01, x11, ty), tz);
}

inline float FractalNoise(Float3 p, std::uint32_t seed) {
  return (ValueNoise(p, seed) * 4.f + ValueNoise(p * 2.03f, seed + 1) * 2.f +
          ValueNoise(p * 4.11f, seed + 2)) / 7.f;
}

}  // namespace hdrf::sim
