// Triangle rasterisation over a grid whose cell centres lie at integer coordinates (camera
// pixels, atlas texels). The fill rule is top-left with edge functions computed in one
// canonical order per edge, so two triangles that share an edge never both claim a cell
// centre on it: in a mesh without overlaps every centre belongs to at most one triangle.
// Used by the UV atlas (overlap check), the texture bake (texels, depth buffers) and renders.
#pragma once

#include <algorithm>
#include <cmath>

#include "common/vec.h"

namespace hdrf::mesh {

namespace raster_detail {
// Edge function of p against the edge a->b, computed with the end points in a canonical order
// so that the edge b->a gives exactly the negated value.
inline double Edge(double ax, double ay, double bx, double by, double px, double py) {
  const bool swap = ax > bx || (ax == bx && ay > by);
  if (swap) return -((ax - bx) * (py - by) - (ay - by) * (px - bx));
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}
// Top-left rule for a counter-clockwise (positive area, y down) triangle: an edge whose
// value is 0 owns the centre when it is a top edge (horizontal, going left) or a left edge
// (going down in y-down coordinates gives negative dy... expressed here on the direction).
inline bool Owns(double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  return dy < 0 || (dy == 0 && dx > 0);
}
}  // namespace raster_detail

// Calls f(x, y, w0, w1, w2) for every cell centre (x, y) in [0, width) x [0, height) inside
// the triangle a, b, c; w are its barycentric coordinates (w0 for a). Degenerate triangles
// cover nothing. Either winding.
template <typename F>
void RasterizeTriangle(Float2 a, Float2 b, Float2 c, int width, int height, F f) {
  using raster_detail::Edge;
  using raster_detail::Owns;
  double ax = a.x, ay = a.y, bx = b.x, by = b.y, cx = c.x, cy = c.y;
  double area = Edge(ax, ay, bx, by, cx, cy);
  if (!(std::abs(area) > 0) || !std::isfinite(area)) return;
  bool swapped = false;
  if (area < 0) {  // make it positive: swap b and c (and their weights back on output)
    std::swap(bx, cx);
    std::swap(by, cy);
    area = -area;
    swapped = true;
  }
  const int x0 = std::max(0, int(std::ceil(std::min({ax, bx, cx}))));
  const int x1 = std::min(width - 1, int(std::floor(std::max({ax, bx, cx}))));
  const int y0 = std::max(0, int(std::ceil(std::min({ay, by, cy}))));
  const int y1 = std::min(height - 1, int(std::floor(std::max({ay, by, cy}))));
  if (x0 > x1 || y0 > y1) return;
  const bool own_a = Owns(bx, by, cx, cy), own_b = Owns(cx, cy, ax, ay), own_c = Owns(ax, ay, bx, by);
  const double inv = 1.0 / area;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double e0 = Edge(bx, by, cx, cy, x, y);  // weight of a
      const double e1 = Edge(cx, cy, ax, ay, x, y);  // weight of b
      const double e2 = Edge(ax, ay, bx, by, x, y);  // weight of c
      if (e0 < 0 || e1 < 0 || e2 < 0) continue;
      if ((e0 == 0 && !own_a) || (e1 == 0 && !own_b) || (e2 == 0 && !own_c)) continue;
      const float w0 = float(e0 * inv), w1 = float(e1 * inv), w2 = float(e2 * inv);
      if (swapped)
        f(x, y, w0, w2, w1);
      else
        f(x, y, w0, w1, w2);
    }
}

}  // namespace hdrf::mesh
