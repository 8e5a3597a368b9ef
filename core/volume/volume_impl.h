// Per-voxel and per-ray steps of the volume, shared by the CPU (volume.cpp) and the GPU
// (volume_cuda.cu, and raycast_driver.h on both): sampling, integration of one voxel, brick marking along
// one depth ray, and ray casting of one pixel.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__CUDACC__)
#include <cuda_fp16.h>
#endif

#include "common/camera.h"
#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"

namespace hdrf::volume {

// The values of one voxel, decoded (and the layout of the full encoding).
struct Voxel {
  float tsdf = 1;                 // signed distance / truncation, in [-1, 1]
  float w = 0;                    // TSDF weight
  Float3 radiance{0, 0, 0};       // HDR radiance, model units
  float nr = 0;                   // normalized radiance (0 where the encoding has none)
  float wr = 0;                   // radiance weight
};

// How voxels are stored (ARCHITECTURE: the paper names memory as its main limitation):
//   kFull     28 B: the values above as floats;
//   kNoNr     24 B: floats, no normalized radiance: the tracker takes NR of the ray-cast
//                   radiance instead (the paper's suggestion);
//   kCompact  12 B: TSDF as snorm16, weights as unsigned 1/1000 fixed point, radiance as
//                   IEEE half floats, no NR.
enum class VoxelEncoding { kFull, kNoNr, kCompact };

// IEEE half <-> float, round to nearest even: in integer arithmetic on the CPU, by the
// hardware on the GPU; both store exactly the same bits (the parity tests check it).
HDRF_HD std::uint16_t FloatToHalf(float f) {
#if defined(__CUDA_ARCH__)
  return __half_as_ushort(__float2half_rn(f));  // the same rounding, in hardware
#else
  std::uint32_t x;
  memcpy(&x, &f, 4);
  const std::uint32_t sign = (x >> 16) & 0x8000u, a = x & 0x7fffffffu;
  if (a >= 0x7f800000u) return std::uint16_t(sign | (a > 0x7f800000u ? 0x7e00u : 0x7c00u));
  if (a >= 0x477ff000u) return std::uint16_t(sign | 0x7c00u);  // rounds past 65504: infinity
  if (a < 0x38800000u) {                                     // below 2^-14: subnormal or zero
    if (a < 0x33000000u) return std::uint16_t(sign);
    const std::uint32_t e = a >> 23, m = (a & 0x7fffffu) | 0x800000u, shift = 126u - e;
    std::uint32_t h = m >> shift;
    const std::uint32_t rem = m & ((1u << shift) - 1u), half = 1u << (shift - 1u);
    if (rem > half || (rem == half && (h & 1u))) ++h;
    return std::uint16_t(sign | h);
  }
  std::uint32_t h = ((((a >> 23) - 112u) << 10) | ((a & 0x7fffffu) >> 13));
  const std::uint32_t rem = a & 0x1fffu;
  if (rem > 0x1000u || (rem == 0x1000u && (h & 1u))) ++h;  // a carry rolls into the exponent
  return std::uint16_t(sign | h);
#endif
}
HDRF_HD float HalfToFloat(std::uint16_t h) {
#if defined(__CUDA_ARCH__)
  return __half2float(__ushort_as_half(h));  // exact either way
#else
  // Exponent and mantissa moved into a float's fields, then scaled by 2^112 (exact: it only
  // rebases the exponent, and turns half subnormals into normal floats); infinities and NaNs
  // keep an all-ones exponent. No branches (the ray cast decodes three per voxel it reads).
  const std::uint32_t sign = std::uint32_t(h & 0x8000u) << 16, em = std::uint32_t(h & 0x7fffu) << 13;
  std::uint32_t bits;
  float v;
  memcpy(&v, &em, 4);
  v *= 5.192296858534828e33f;  // 2^112
  memcpy(&bits, &v, 4);
  const std::uint32_t special = (h & 0x7c00u) == 0x7c00u ? 0x7f800000u : 0u;
  const std::uint32_t x = sign | bits | special;
  float f;
  memcpy(&f, &x, 4);
  return f;
#endif
}

struct FullVoxel {
  Voxel v;
  static constexpr bool kStoresNr = true;
  HDRF_HD float Tsdf() const { return v.tsdf; }
  HDRF_HD float W() const { return v.w; }
  HDRF_HD float Wr() const { return v.wr; }
  HDRF_HD Float3 Radiance() const { return v.radiance; }
  HDRF_HD float Nr() const { return v.nr; }
  HDRF_HD Voxel Decode() const { return v; }
  HDRF_HD void Store(const Voxel& x) { v = x; }
  HDRF_HD void StoreDistance(float t, float w) { v.tsdf = t, v.w = w; }  // the rest kept
};
struct NoNrVoxel {
  float tsdf = 1, w = 0;
  Float3 radiance{0, 0, 0};
  float wr = 0;
  static constexpr bool kStoresNr = false;
  HDRF_HD float Tsdf() const { return tsdf; }
  HDRF_HD float W() const { return w; }
  HDRF_HD float Wr() const { return wr; }
  HDRF_HD Float3 Radiance() const { return radiance; }
  HDRF_HD float Nr() const { return 0.f; }
  HDRF_HD Voxel Decode() const { return {tsdf, w, radiance, 0.f, wr}; }
  HDRF_HD void Store(const Voxel& x) {
    tsdf = x.tsdf;
    w = x.w;
    radiance = x.radiance;
    wr = x.wr;
  }
  HDRF_HD void StoreDistance(float t, float weight) { tsdf = t, w = weight; }
};
struct CompactVoxel {
  std::int16_t tsdf = 32767;
  std::uint16_t w = 0, r = 0, g = 0, b = 0, wr = 0;
  static constexpr bool kStoresNr = false;
  static constexpr float kWeightStep = 1e-3f;  // weights up to 65.5 (caps are checked)
  HDRF_HD static std::uint16_t Weight(float x) {
    const float q = x / kWeightStep + 0.5f;
    return std::uint16_t(q >= 65535.f ? 65535.f : (q < 0.f ? 0.f : q));
  }
  HDRF_HD float Tsdf() const { return float(tsdf) * (1.f / 32767.f); }
  HDRF_HD float W() const { return float(w) * kWeightStep; }
  HDRF_HD float Wr() const { return float(wr) * kWeightStep; }
  HDRF_HD Float3 Radiance() const { return {HalfToFloat(r), HalfToFloat(g), HalfToFloat(b)}; }
  HDRF_HD float Nr() const { return 0.f; }
  HDRF_HD Voxel Decode() const { return {Tsdf(), W(), Radiance(), 0.f, Wr()}; }
  HDRF_HD void Store(const Voxel& x) {
    StoreDistance(x.tsdf, x.w);
    r = FloatToHalf(x.radiance.x);
    g = FloatToHalf(x.radiance.y);
    b = FloatToHalf(x.radiance.z);
    wr = Weight(x.wr);
  }
  // The distance and its weight only; the radiance's bits kept (re-encoding them would give
  // the same bits: every half converts to a float and back exactly).
  HDRF_HD void StoreDistance(float t_in, float weight) {
    const float t = t_in > 1.f ? 1.f : (t_in < -1.f ? -1.f : t_in);
    tsdf = std::int16_t(RoundToInt(t * 32767.f));
    w = Weight(weight);
  }
};

inline constexpr int EncodingBytes(VoxelEncoding e) {
  return e == VoxelEncoding::kCompact ? int(sizeof(CompactVoxel))
                                      : (e == VoxelEncoding::kNoNr ? int(sizeof(NoNrVoxel)) : int(sizeof(FullVoxel)));
}
inline constexpr bool EncodingStoresNr(VoxelEncoding e) { return e == VoxelEncoding::kFull; }

// Calls f(V{}) with the encoding's type (host code).
template <typename F>
decltype(auto) VisitEncoding(VoxelEncoding e, F&& f) {
  switch (e) {
    case VoxelEncoding::kNoNr: return f(NoNrVoxel{});
    case VoxelEncoding::kCompact: return f(CompactVoxel{});
    default: return f(FullVoxel{});
  }
}

inline constexpr int kBrick = 8;

// ---- Brick addressing -------------------------------------------------------------------------
// The volume has no fixed extent: a brick (8^3 voxels) is named by its integer coordinates,
// each within [-kBrickRange, kBrickRange) (at 1 cm voxels, 2.6 km either way of the first
// camera), packed into a 64-bit key whose order is z, then y, then x. Bricks are found
// through an open-addressing hash table (linear probing, a power-of-two capacity kept at
// most half full), the same table layout on the CPU and the GPU.
inline constexpr int kBrickRange = 1 << 15;
inline constexpr std::uint64_t kEmptyKey = ~std::uint64_t(0);

// Unsigned arithmetic: any int (a coordinate read from a damaged file too) is tested
// without overflow.
HDRF_HD bool BrickInRange(int bx, int by, int bz) {
  constexpr unsigned kOffset = unsigned(kBrickRange), kSpan = 2u * unsigned(kBrickRange);
  return unsigned(bx) + kOffset < kSpan && unsigned(by) + kOffset < kSpan && unsigned(bz) + kOffset < kSpan;
}
HDRF_HD std::uint64_t BrickKey(int bx, int by, int bz) {
  return (std::uint64_t(unsigned(bz + kBrickRange)) << 32) | (std::uint64_t(unsigned(by + kBrickRange)) << 16) |
         std::uint64_t(unsigned(bx + kBrickRange));
}
HDRF_HD void DecodeBrickKey(std::uint64_t key, int* bx, int* by, int* bz) {
  *bx = int(key & 0xffffu) - kBrickRange;
  *by = int((key >> 16) & 0xffffu) - kBrickRange;
  *bz = int((key >> 32) & 0xffffu) - kBrickRange;
}
// The 4x4x4-brick group holding a brick (empty-space skipping).
HDRF_HD std::uint64_t GroupKey(int bx, int by, int bz) { return BrickKey(bx >> 2, by >> 2, bz >> 2); }
HDRF_HD std::uint32_t HashBrickKey(std::uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdull;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ull;
  k ^= k >> 33;
  return std::uint32_t(k);
}

// A hash table's arrays, wherever they live: key -> value (a pool slot), -1 where absent.
struct HashView {
  const std::uint64_t* keys = nullptr;
  const int* values = nullptr;
  std::uint32_t mask = 0;  // capacity - 1
  HDRF_HD int Find(std::uint64_t key) const {
    std::uint32_t h = HashBrickKey(key) & mask;
    for (std::uint32_t probes = 0; probes <= mask; ++probes) {
      const std::uint64_t k = keys[h];
      if (k == key) return values[h];
      if (k == kEmptyKey) return -1;
      h = (h + 1) & mask;
    }
    return -1;
  }
};

// The volume's arrays, wherever they live, for voxel encoding V.
template <typename V>
struct VolumeView {
  using Encoded = V;                     // the voxel encoding
  HashView bricks;                       // brick key -> pool slot
  HashView groups;                       // group key -> any brick allocated in the group
  V* pool = nullptr;                     // 512 voxels per allocated brick
  float voxel_m = 0, trunc_m = 0;

  HDRF_HD int Slot(int bx, int by, int bz) const {
    return BrickInRange(bx, by, bz) ? bricks.Find(BrickKey(bx, by, bz)) : -1;
  }
  HDRF_HD bool BrickAllocated(int bx, int by, int bz) const { return Slot(bx, by, bz) >= 0; }
  HDRF_HD bool GroupAllocated(int bx, int by, int bz) const {
    return BrickInRange(bx, by, bz) && groups.Find(GroupKey(bx, by, bz)) >= 0;
  }
  HDRF_HD const V* Get(int x, int y, int z) const {
    const int b = Slot(x >> 3, y >> 3, z >> 3);
    return b < 0 ? nullptr : &pool[long(b) * 512 + ((z & 7) * 8 + (y & 7)) * 8 + (x & 7)];
  }
  // Voxel-centre grid coordinates of a world point.
  HDRF_HD Float3 Grid(Float3 p) const { return p * (1.f / voxel_m) - Float3{0.5f, 0.5f, 0.5f}; }

  // The pool slots of the eight corners (x..x+1, y..y+1, z..z+1) of a trilinear cell, each
  // distinct brick looked up once (a cell spans one brick, or two to eight at brick faces);
  // slot[k] < 0 where that corner's brick is absent. `hint` is a brick already looked up.
  struct BrickHint {
    int bx = 0, by = 0, bz = 0, slot = -1;
    bool valid = false;
  };
  HDRF_HD void CornerSlots(int x, int y, int z, const BrickHint& hint, int slot[8]) const {
    const int bx0 = x >> 3, by0 = y >> 3, bz0 = z >> 3;
    const int sx = (x & 7) == 7 ? 1 : 0, sy = (y & 7) == 7 ? 1 : 0, sz = (z & 7) == 7 ? 1 : 0;
    for (int dz = 0; dz <= sz; ++dz)
      for (int dy = 0; dy <= sy; ++dy)
        for (int dx = 0; dx <= sx; ++dx) {
          const int bx = bx0 + dx, by = by0 + dy, bz = bz0 + dz;
          slot[dz * 4 + dy * 2 + dx] =
              hint.valid && bx == hint.bx && by == hint.by && bz == hint.bz ? hint.slot : Slot(bx, by, bz);
        }
    // Corners whose brick is the cell's first along an axis share that entry.
    for (int k = 0; k < 8; ++k) {
      const int dx = (k & 1) & sx, dy = ((k >> 1) & 1) & sy, dz = (k >> 2) & sz;
      if (dx != (k & 1) || dy != ((k >> 1) & 1) || dz != (k >> 2)) slot[k] = slot[dz * 4 + dy * 2 + dx];
    }
  }
  HDRF_HD const V* Corner(const int slot[8], int x, int y, int z, int k) const {
    const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
    if (slot[k] < 0) return nullptr;
    const int cx = x + dx, cy = y + dy, cz = z + dz;
    return &pool[long(slot[k]) * 512 + ((cz & 7) * 8 + (cy & 7)) * 8 + (cx & 7)];
  }

  // The eight corners of the trilinear cell at (x, y, z) when they all lie in one brick (a
  // cell off the brick's last voxel along every axis: 343 of its 512), else nullptr: corner
  // k = dx + 2 dy + 4 dz is at base + dx + 8 dy + 64 dz. Null too where that brick is absent.
  HDRF_HD const V* CellInOneBrick(int x, int y, int z, const BrickHint& hint) const {
    if ((x & 7) == 7 || (y & 7) == 7 || (z & 7) == 7) return nullptr;
    const int bx = x >> 3, by = y >> 3, bz = z >> 3;
    const int slot = hint.valid && bx == hint.bx && by == hint.by && bz == hint.bz ? hint.slot : Slot(bx, by, bz);
    return slot < 0 ? nullptr : &pool[long(slot) * 512 + ((z & 7) * 8 + (y & 7)) * 8 + (x & 7)];
  }
  // The short way is the CPU's: on the GPU a second path in every sample cost registers and
  // split warps (the ray cast took 1.6x as long on an H100), and the GPU's look-ups are cheap.
  HDRF_HD static bool ShortWay(bool wanted) {
#if defined(__CUDA_ARCH__)
    (void)wanted;
    return false;
#else
    return wanted;
#endif
  }

  // Calls visit(voxel, weight) for each present corner of the trilinear cell holding p, in
  // corner order k = dx + 2 dy + 4 dz, with its trilinear weight. A cell inside one brick takes
  // the short way (one look-up, fixed offsets) on the CPU unless `short_way` is off (tests);
  // both ways visit the same corners in the same order with the same weights, so the samples
  // built on this give the same bits either way.
  template <typename Visit>
  HDRF_HD void ForEachCorner(Float3 p, const BrickHint& hint, bool short_way, Visit&& visit) const {
    const Float3 g = Grid(p);
    const int x = FloorToInt(g.x), y = FloorToInt(g.y), z = FloorToInt(g.z);
    const float ax = g.x - float(x), ay = g.y - float(y), az = g.z - float(z);
    const float wx[2] = {1 - ax, ax}, wy[2] = {1 - ay, ay}, wz[2] = {1 - az, az};
    const bool in_one = (x & 7) != 7 && (y & 7) != 7 && (z & 7) != 7;
    if (ShortWay(short_way) && in_one) {
      const V* base = CellInOneBrick(x, y, z, hint);
      if (!base) return;  // its one brick is absent
      HDRF_UNROLL
      for (int k = 0; k < 8; ++k)
        visit(base[(k & 1) + 8 * ((k >> 1) & 1) + 64 * (k >> 2)], wx[k & 1] * wy[(k >> 1) & 1] * wz[k >> 2]);
      return;
    }
    int slot[8];
    CornerSlots(x, y, z, hint, slot);
    for (int k = 0; k < 8; ++k)
      if (const V* v = Corner(slot, x, y, z, k)) visit(*v, wx[k & 1] * wy[(k >> 1) & 1] * wz[k >> 2]);
  }

  // Trilinear TSDF over the observed corners, renormalised; undefined (false) when the
  // observed corners carry less than half of the interpolation weight.
  HDRF_HD bool SampleTsdf(Float3 p, float* out, const BrickHint& hint = BrickHint{}, bool short_way = true) const {
    float acc = 0.f, wsum = 0.f;
    ForEachCorner(p, hint, short_way, [&](const V& v, float w) {
      if (v.W() <= 0.f) return;
      acc += w * v.Tsdf();
      wsum += w;
    });
    if (wsum < 0.5f) return false;
    *out = acc / wsum;
    return true;
  }

  // Trilinear radiance and NR over the corners with radiance weight; false if none has any.
  HDRF_HD bool SampleRadiance(Float3 p, Float3* rad, float* nr, const BrickHint& hint = BrickHint{},
                              bool short_way = true) const {
    RadianceSum sum;
    ForEachCorner(p, hint, short_way, [&](const V& v, float w) { sum.Add(v, w); });
    return sum.Get(rad, nr);
  }
  // The same from the cell's eight corners already found (corner k = dx + 2 dy + 4 dz, as
  // GradientOfVoxels gives them): the same corners, order and weights, so the same bits.
  HDRF_HD bool SampleRadianceOfCell(Float3 p, const V* const corner[8], Float3* rad, float* nr) const {
    const Float3 g = Grid(p);
    const float ax = g.x - float(FloorToInt(g.x)), ay = g.y - float(FloorToInt(g.y)), az = g.z - float(FloorToInt(g.z));
    const float wx[2] = {1 - ax, ax}, wy[2] = {1 - ay, ay}, wz[2] = {1 - az, az};
    RadianceSum sum;
    for (int k = 0; k < 8; ++k) sum.Add(*corner[k], wx[k & 1] * wy[(k >> 1) & 1] * wz[k >> 2]);
    return sum.Get(rad, nr);
  }
  struct RadianceSum {
    Float3 r{0, 0, 0};
    float nn = 0.f, wsum = 0.f;
    HDRF_HD void Add(const V& v, float w) {
      if (v.Wr() <= 0.f) return;
      r += v.Radiance() * w;
      nn += v.Nr() * w;
      wsum += w;
    }
    HDRF_HD bool Get(Float3* rad, float* nr) const {
      if (wsum < 1e-3f) return false;
      *rad = r / wsum;
      *nr = nn / wsum;
      return true;
    }
  };

  // Normal from the TSDF gradient: central differences of trilinear samples one voxel either
  // side of p along each axis. `hint` (a brick near p already looked up) spares look-ups in
  // that brick. Where the 32 voxels those six samples read are all observed, the difference
  // of two samples is the trilinear interpolation at p of the voxels' own central
  // differences: each voxel is read once (32 reads, not the samples' 48) with one set of
  // weights (GradientOfVoxels); elsewhere the six samples, each renormalised over its
  // observed corners, as before (GradientOfSamples). The two agree to rounding.
  // `cell`, where given, receives the eight corners of p's cell when the 32 voxels gave the
  // normal (SampleRadianceOfCell reads them), else cell[0] = nullptr.
  HDRF_HD bool Gradient(Float3 p, Float3* nrm, const BrickHint& hint = BrickHint{}, const V** cell = nullptr) const {
    Float3 g;
    if (cell) cell[0] = nullptr;
    if (!GradientOfVoxels(p, hint, &g, cell) && !GradientOfSamples(p, hint, &g)) return false;
    const float len = Length(g);
    if (len < 1e-6f) return false;
    *nrm = g / len;
    return true;
  }
  HDRF_HD bool GradientOfSamples(Float3 p, const BrickHint& hint, Float3* g) const {
    const float h = voxel_m;
    float fx0, fx1, fy0, fy1, fz0, fz1;
    if (!SampleTsdf(p - Float3{h, 0, 0}, &fx0, hint) || !SampleTsdf(p + Float3{h, 0, 0}, &fx1, hint) ||
        !SampleTsdf(p - Float3{0, h, 0}, &fy0, hint) || !SampleTsdf(p + Float3{0, h, 0}, &fy1, hint) ||
        !SampleTsdf(p - Float3{0, 0, h}, &fz0, hint) || !SampleTsdf(p + Float3{0, 0, h}, &fz1, hint))
      return false;
    *g = Float3{fx1 - fx0, fy1 - fy0, fz1 - fz0};
    return true;
  }
  // The cell (x..x+1, y..y+1, z..z+1) holding p and the voxels one step out along each axis
  // from its corners: the lines x-1..x+2 at the cell's four (y, z), then y-1 and y+2 at its
  // four (x, z), then z-1 and z+2 at its four (x, y). False where one is absent or unobserved.
  HDRF_HD bool GradientOfVoxels(Float3 p, const BrickHint& hint, Float3* out, const V** cell = nullptr) const {
    const Float3 q = Grid(p);
    const int x = FloorToInt(q.x), y = FloorToInt(q.y), z = FloorToInt(q.z);
    const float ax = q.x - float(x), ay = q.y - float(y), az = q.z - float(z);
    // Positions x-1..x+2 (and so on) as index 0..3: the brick (0: that of x-1, 1: the next)
    // and the place in it. The bricks are the 2 x 2 x 2 from the one holding (x-1, y-1, z-1),
    // those the lines reach each looked up once.
    const int bx0 = (x - 1) >> 3, by0 = (y - 1) >> 3, bz0 = (z - 1) >> 3;
    int ox[4], oy[4], oz[4], lx[4], ly[4], lz[4];
    HDRF_UNROLL_HOST
    for (int i = 0; i < 4; ++i) {
      ox[i] = ((x - 1 + i) >> 3) - bx0, lx[i] = (x - 1 + i) & 7;
      oy[i] = ((y - 1 + i) >> 3) - by0, ly[i] = (y - 1 + i) & 7;
      oz[i] = ((z - 1 + i) >> 3) - bz0, lz[i] = ((z - 1 + i) & 7) * 64;
    }
    int slot[8];
    for (int k = 0; k < 8; ++k) {
      const int dx = k & 1, dy = (k >> 1) & 1, dz = k >> 2;
      if (dx > ox[3] || dy > oy[3] || dz > oz[3]) continue;
      const int bx = bx0 + dx, by = by0 + dy, bz = bz0 + dz;
      slot[k] = hint.valid && bx == hint.bx && by == hint.by && bz == hint.bz ? hint.slot : Slot(bx, by, bz);
    }
    bool ok = true;
    auto at = [&](int i, int j, int l) HDRF_INLINE_LAMBDA {  // the TSDF at (x-1+i, y-1+j, z-1+l); ok false where none
      const int s = slot[ox[i] + 2 * oy[j] + 4 * oz[l]];
      if (s < 0) {
        ok = false;
        return 0.f;
      }
      const V& v = pool[long(s) * 512 + lz[l] + ly[j] * 8 + lx[i]];
      ok = ok && v.W() > 0.f;
      return v.Tsdf();
    };
    float c[8], dx[8], dy[8], dz[8];  // per corner k = i + 2 j + 4 l: the TSDF, its differences
    HDRF_UNROLL_HOST
    for (int k = 0; k < 8; k += 2) {  // the x lines
      const int j = 1 + ((k >> 1) & 1), l = 1 + (k >> 2);
      const float lo = at(0, j, l), hi = at(3, j, l);
      c[k] = at(1, j, l);
      c[k + 1] = at(2, j, l);
      dx[k] = c[k + 1] - lo;
      dx[k + 1] = hi - c[k];
    }
    HDRF_UNROLL_HOST
    for (int k = 0; k < 8; ++k) {  // the y lines: k the corner at y, k + 2 at y + 1
      if ((k >> 1) & 1) continue;
      const int i = 1 + (k & 1), l = 1 + (k >> 2);
      const float lo = at(i, 0, l), hi = at(i, 3, l);
      dy[k] = c[k + 2] - lo;
      dy[k + 2] = hi - c[k];
    }
    HDRF_UNROLL_HOST
    for (int k = 0; k < 4; ++k) {  // the z lines: k the corner at z, k + 4 at z + 1
      const int i = 1 + (k & 1), j = 1 + (k >> 1);
      const float lo = at(i, j, 0), hi = at(i, j, 3);
      dz[k] = c[k + 4] - lo;
      dz[k + 4] = hi - c[k];
    }
    if (!ok) return false;
    const float wx[2] = {1 - ax, ax}, wy[2] = {1 - ay, ay}, wz[2] = {1 - az, az};
    Float3 g{0, 0, 0};
    HDRF_UNROLL_HOST
    for (int k = 0; k < 8; ++k) {
      const float w = wx[k & 1] * wy[(k >> 1) & 1] * wz[k >> 2];
      g.x += w * dx[k];
      g.y += w * dy[k];
      g.z += w * dz[k];
    }
    *out = g;
    if (cell) {
      for (int k = 0; k < 8; ++k) {
        const int i = 1 + (k & 1), j = 1 + ((k >> 1) & 1), l = 1 + (k >> 2);
        cell[k] = &pool[long(slot[ox[i] + 2 * oy[j] + 4 * oz[l]]) * 512 + lz[l] + ly[j] * 8 + lx[i]];
      }
    }
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
  float voxel_m, trunc_m, max_weight, max_radiance_weight, tau0, cos_tau1;
};

// The most bricks ForBricksAlongRay names for one ray.
HDRF_HD int MaxBricksAlongRay(float trunc_m, float voxel_m) { return int(2.f * trunc_m / (0.5f * voxel_m * kBrick)) + 2; }

// Brick coordinates along the depth ray of pixel (x, y) within the truncation band; calls
// mark(bx, by, bz) for each (a brick may be named more than once; bricks out of range are
// skipped).
template <typename Mark>
HDRF_HD void ForBricksAlongRay(const IntegrateArgs& a, const RigidTransform& T_world_camera, int x, int y,
                               Mark&& mark) {
  const float z = a.depth(x, y);
  if (!(z > 0.f)) return;
  const float bs = a.voxel_m * kBrick;
  const Float3 pc = a.cam.BackProject(float(x), float(y), z);
  const float len = Length(pc);
  const Float3 dir = pc / len;
  for (float d = len - a.trunc_m; d <= len + a.trunc_m; d += 0.5f * bs) {
    const Float3 pw = T_world_camera.Apply(dir * d);
    const Float3 g = pw / bs;
    if (!(fabsf(g.x) < float(kBrickRange - 1) && fabsf(g.y) < float(kBrickRange - 1) && fabsf(g.z) < float(kBrickRange - 1)))
      continue;
    mark(FloorToInt(g.x), FloorToInt(g.y), FloorToInt(g.z));
  }
}

// Voxel i (0..511) of the brick at brick coordinates (bx, by, bz) seen in the frame: its
// position in the camera, the pixel it projects to and its signed distance to the depth
// there; false where it is not updated (behind the camera, outside the image, no depth,
// further than the truncation behind the surface).
struct VoxelInView {
  Float3 pc;
  int u, v;
  float sdf;
};
HDRF_HD bool ProjectVoxel(const IntegrateArgs& a, int bx, int by, int bz, int i, VoxelInView* out) {
  const int lx = i & 7, ly = (i >> 3) & 7, lz = i >> 6;
  const float vs = a.voxel_m, trunc = a.trunc_m;
  const Float3 pw = Float3{(float(bx * 8 + lx) + 0.5f) * vs, (float(by * 8 + ly) + 0.5f) * vs,
                                      (float(bz * 8 + lz) + 0.5f) * vs};
  const Float3 pc = a.T_camera_world.Apply(pw);
  if (pc.z <= 0.05f) return false;
  const Float2 px = a.cam.Project(pc);
  const int u = RoundToInt(px.x), v = RoundToInt(px.y);
  if (u < 0 || v < 0 || u >= a.cam.width || v >= a.cam.height) return false;
  const float zd = a.depth(u, v);
  if (!(zd > 0.f)) return false;
  const float sdf = zd - pc.z;
  if (sdf < -trunc) return false;
  *out = {pc, u, v, sdf};
  return true;
}

// Updates a voxel ProjectVoxel found in view. Returns bit 0: TSDF updated, bit 1: radiance
// updated.
template <typename V>
HDRF_HD int UpdateVoxel(const IntegrateArgs& a, const VoxelInView& in, V& stored) {
  const float trunc = a.trunc_m;
  const Float3 pc = in.pc;
  const int u = in.u, v = in.v;
  const float sdf = in.sdf;
  const float f = sdf / trunc < 1.f ? sdf / trunc : 1.f;
  const Float3 ray = Normalized(pc);
  const Float3 nrm = a.normals(u, v);
  const float cosv = fabsf(Dot(nrm, ray));
  const float wf = Length(nrm) > 0.f ? (cosv > 0.05f ? cosv : 0.05f) : 0.05f;
  // The distance first; the radiance is decoded and stored again only where it changes (a
  // voxel in free space or out of the radiance's reach keeps its radiance's bits).
  const float w0 = stored.W(), t0 = stored.Tsdf();
  const float tsdf = (w0 * t0 + wf * f) / (w0 + wf);
  const float w = w0 + wf < a.max_weight ? w0 + wf : a.max_weight;
  if (fabsf(sdf) < trunc && a.radiance.data && a.max_confidence(u, v) > a.tau0 && cosv >= a.cos_tau1) {
    const float wr = a.confidence(u, v);
    if (wr > 0.f) {
      Voxel vx = stored.Decode();
      vx.tsdf = tsdf;
      vx.w = w;
      const Float3 live = a.radiance(u, v) * a.radiance_scale;
      vx.radiance = (vx.radiance * vx.wr + live * wr) / (vx.wr + wr);
      if constexpr (V::kStoresNr) vx.nr = (vx.nr * vx.wr + a.nr(u, v) * wr) / (vx.wr + wr);
      vx.wr = vx.wr + wr < a.max_radiance_weight ? vx.wr + wr : a.max_radiance_weight;
      stored.Store(vx);
      return 3;
    }
  }
  stored.StoreDistance(tsdf, w);
  return 1;
}

// Updates voxel i (0..511) of the brick at brick coordinates (bx, by, bz): ProjectVoxel, then
// UpdateVoxel. Returns bit 0: TSDF updated, bit 1: radiance updated.
template <typename V>
HDRF_HD int IntegrateVoxel(const IntegrateArgs& a, int bx, int by, int bz, int i, V& stored) {
  VoxelInView in;
  return ProjectVoxel(a, bx, by, bz, i, &in) ? UpdateVoxel(a, in, stored) : 0;
}

}  // namespace hdrf::volume
