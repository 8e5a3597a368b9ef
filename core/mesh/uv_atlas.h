// UV atlas for a scanned mesh: charts, a planar parameterisation per chart, and packing
// into one texture with padding, at a chosen texel density (metres per texel).
//
// Charts grow over edge-adjacent triangles whose (smoothed) normals stay within an angle
// of the chart's seed normal; each chart is projected orthographically on the plane
// across that normal, so no triangle flips. A chart whose projection overlaps itself
// (checked by rasterising it at the texel density) is split again with a smaller angle.
// Charts are turned to their principal axes and packed on shelves, each with `padding`
// texels of margin on every side for filtering and mip levels.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "mesh/mesh.h"

namespace hdrf::mesh {

struct AtlasOptions {
  double texel_m = 0.002;      // texel size on the surface (2 mm); ignored when fit_size > 0
  int fit_size = 0;            // > 0: choose the density so that the atlas fits fit_size^2
  int padding = 2;             // texels around every chart
  int max_size = 8192;         // the atlas may not exceed this in either direction
  double chart_angle_deg = 40; // largest angle between a triangle's normal and its chart's
  void Check() const;          // throws SettingError naming the option
};

struct Chart {
  int x0 = 0, y0 = 0, width = 0, height = 0;  // its rectangle in the atlas (padding included)
  int triangles = 0;
};

struct Atlas {
  Mesh mesh;                          // the input, vertices split along chart seams
  std::vector<std::int32_t> source;   // per vertex: its index in the input mesh
  std::vector<Float2> texel;          // per vertex: atlas position in texels (centres at integers, y down)
  std::vector<std::int32_t> chart;    // per triangle
  std::vector<Chart> charts;
  int width = 0, height = 0;
  double texel_m = 0;                 // the density actually used
  int padding = 0;
  long overlap_splits = 0;            // charts that overlapped themselves and were split again
  // Normalised texture coordinates of vertex v: origin top-left (glTF) or bottom-left (OBJ).
  Float2 UvTopLeft(std::size_t v) const;
  Float2 UvBottomLeft(std::size_t v) const;
  double Utilisation() const;         // share of the atlas covered by triangles
};

// `progress(fraction)` returning false cancels (throws hdrf::Cancelled). Throws SettingError
// when the requested density needs a texture larger than max_size (naming the density that
// would fit). Triangles without area are left out; an empty mesh gives an empty atlas.
Atlas BuildAtlas(const Mesh& m, const AtlasOptions& o, const std::function<bool(double)>& progress = {});

// Texels claimed by more than one triangle (0 for a valid atlas), for tests.
long CountOverlappingTexels(const Atlas& a);

}  // namespace hdrf::mesh
