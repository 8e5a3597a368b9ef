// Per-pixel steps of imaging, shared by the drivers of both devices (imaging_driver.h,
// tracking/pyramid_driver.h). Both backends call exactly these functions, so they agree to the bit
// wherever the arithmetic is plain IEEE (the CUDA build is compiled without FMA contraction).
#pragma once

#include "common/camera.h"
#include "common/host_device.h"
#include "common/image_view.h"
#include "common/vec.h"

namespace hdrf::imaging {

// ---- Pyramids -------------------------------------------------------------------------------
HDRF_HD float Mean2x2(ImageView<const float> in, int x, int y) {
  return 0.25f * (in(2 * x, 2 * y) + in(2 * x + 1, 2 * y) + in(2 * x, 2 * y + 1) + in(2 * x + 1, 2 * y + 1));
}
// Mean of the valid neighbours within 5 % of the top-left sample's depth (0 stays 0).
HDRF_HD float DownsampleDepthPixel(ImageView<const float> d, int x, int y) {
  const float c = d(2 * x, 2 * y);
  if (!(c > 0.f)) return 0.f;
  float sum = 0.f;
  int n = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const float v = d(2 * x + dx, 2 * y + dy);
      if (v > 0.f && fabsf(v - c) < 0.05f * c) {
        sum += v;
        ++n;
      }
    }
  return sum / float(n);
}

// ---- Bilateral depth filter ---------------------------------------------------------------
inline constexpr int kBilateralMaxRadius = 5;
inline constexpr int kBilateralBins = 256;
struct BilateralTables {
  int radius = 3;
  float to_bin = 0;  // range-table bins per metre of |dz|
  float spatial[(2 * kBilateralMaxRadius + 1) * (2 * kBilateralMaxRadius + 1)];
  float range[kBilateralBins + 1];  // last bin: beyond 3 sigma, weight 0
};
HDRF_HD float BilateralPixel(ImageView<const float> d, const BilateralTables& t, int x, int y) {
  const float c = d(x, y);
  if (!(c > 0.f && c <= 3.0e38f)) return 0.f;  // none, or not finite: no depth
  const int r = t.radius, side = 2 * r + 1;
  float sw = 0.f, sv = 0.f;
  auto tap = [&](float v, int k) {
    if (!(v > 0.f && v <= 3.0e38f)) return;
    // The bin in float first: a depth difference of kilometres (a wrong depth scale) or an
    // infinite one would overflow an int conversion and index outside the table.
    const float fb = fabsf(v - c) * t.to_bin;
    const int bin = fb < float(kBilateralBins) ? int(fb) : kBilateralBins;
    const float wgt = t.spatial[k] * t.range[bin];
    sw += wgt;
    sv += wgt * v;
  };
#if !defined(__CUDA_ARCH__)
  // On the CPU, a pixel whose window lies inside the image reads its rows without the
  // border checks: the same taps in the same order, so the same bits.
  if (x >= r && y >= r && x + r < d.width && y + r < d.height) {
    for (int dy = -r; dy <= r; ++dy) {
      const float* row = &d(x - r, y + dy);
      const int k0 = (dy + r) * side;
      for (int i = 0; i < side; ++i) tap(row[i], k0 + i);
    }
    return sv / sw;
  }
#endif
  for (int dy = -r; dy <= r; ++dy) {
    const int yy = y + dy;
    if (yy < 0 || yy >= d.height) continue;
    for (int dx = -r; dx <= r; ++dx) {
      const int xx = x + dx;
      if (xx < 0 || xx >= d.width) continue;
      tap(d(xx, yy), (dy + r) * side + dx + r);
    }
  }
  return sv / sw;
}

// ---- Vertex and normal maps ---------------------------------------------------------------
HDRF_HD Float3 VertexPixel(ImageView<const float> d, const PinholeCamera& cam, int x, int y) {
  const float z = d(x, y);
  return z > 0.f ? cam.BackProject(float(x), float(y), z) : Float3{0, 0, 0};
}
// Normal from the right and lower neighbours, facing the camera; zero where undefined.
HDRF_HD Float3 NormalPixel(ImageView<const Float3> v, float max_jump, int x, int y) {
  const Float3 zero{0, 0, 0};
  if (x + 1 >= v.width || y + 1 >= v.height) return zero;
  const Float3 c = v(x, y), r = v(x + 1, y), b = v(x, y + 1);
  if (c.z <= 0.f || r.z <= 0.f || b.z <= 0.f) return zero;
  if (fabsf(r.z - c.z) > max_jump * c.z || fabsf(b.z - c.z) > max_jump * c.z) return zero;
  Float3 n = Cross(b - c, r - c);
  const float len = Length(n);
  if (len <= 0.f) return zero;
  n = n / len;
  if (Dot(n, c) > 0.f) n = -n;
  return n;
}

// Central differences (0 on the border).
HDRF_HD float GradXPixel(ImageView<const float> im, int x, int y) {
  return (x > 0 && x + 1 < im.width) ? 0.5f * (im(x + 1, y) - im(x - 1, y)) : 0.f;
}
HDRF_HD float GradYPixel(ImageView<const float> im, int x, int y) {
  return (y > 0 && y + 1 < im.height) ? 0.5f * (im(x, y + 1) - im(x, y - 1)) : 0.f;
}

// A bilinear sampling position in images of one size, found once for several images.
struct BilinearAt {
  int ix = 0, iy = 0;
  float ax = 0, ay = 0;
  // False when a needed neighbour is outside a width x height image.
  HDRF_HD bool Set(int width, int height, float x, float y) {
    if (x < 0.f || y < 0.f || x > float(width) - 1.001f || y > float(height) - 1.001f) return false;
    ix = int(x), iy = int(y);
    ax = x - float(ix), ay = y - float(iy);
    return true;
  }
  HDRF_HD float operator()(ImageView<const float> img) const {
    return (1 - ay) * ((1 - ax) * img(ix, iy) + ax * img(ix + 1, iy)) +
           ay * ((1 - ax) * img(ix, iy + 1) + ax * img(ix + 1, iy + 1));
  }
};

// Bilinear sample; false when a needed neighbour is outside.
HDRF_HD bool SampleBilinear(ImageView<const float> img, float x, float y, float* out) {
  BilinearAt at;
  if (!at.Set(img.width, img.height, x, y)) return false;
  *out = at(img);
  return true;
}

// Grey level in [0, 1] of the delivered colour: the brightness-constancy baseline's input.
HDRF_HD float RawIntensityPixel(Rgb8 c) { return float(c.r + c.g + c.b) / 765.f; }

}  // namespace hdrf::imaging
