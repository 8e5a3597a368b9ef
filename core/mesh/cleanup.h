// Mesh clean-up for export: what an artist's tools choke on removed, what is missing filled,
// every change counted. Operates on the extracted HDR mesh (mesh.h).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "mesh/mesh.h"

namespace hdrf::mesh {

struct Box {
  Float3 min, max;  // metres, in the mesh's frame
};

struct CleanOptions {
  double weld_tolerance = 1e-5;      // metres: vertices closer than this become one
  double min_piece_area = 0.01;      // m^2: connected pieces smaller than this are dropped (0 keeps all)
  double max_hole_perimeter = 0.25;  // metres: boundary loops up to this long are filled (0 fills none)
  bool fill_radiance = true;         // vertices without radiance take their neighbours'
  std::optional<Box> crop;           // keep only triangles with every vertex inside
  void Check() const;                // throws SettingError naming the option
};

struct CleanReport {
  int welded = 0;              // vertices merged into another
  int degenerate_removed = 0;  // zero-area (or repeated-vertex) triangles
  int duplicate_removed = 0;   // triangles repeating another's vertices
  int cropped = 0;             // triangles outside the crop box
  int pieces_kept = 0, pieces_removed = 0;
  int holes_filled = 0, holes_left = 0;  // boundary loops closed / left open
  int radiance_filled = 0;     // vertices whose radiance came from neighbours
  int radiance_missing = 0;    // vertices left without (their piece has none at all)
};

struct CleanMesh {
  Mesh mesh;
  std::vector<std::uint8_t> radiance_filled;  // per vertex: 1 = radiance from neighbours (or a hole's fill)
  std::vector<std::int32_t> source;           // per vertex: its index in the input, -1 for a hole's centre
  CleanReport report;
};

// The steps in order: crop, weld, drop degenerate and duplicate triangles, drop small
// pieces, fill small holes, fill missing radiance; unreferenced vertices removed. Pieces
// whose vertices all lack radiance are dropped (reported in pieces_removed).
CleanMesh Clean(const Mesh& in, const CleanOptions& o);

// Connected pieces (through shared vertices) and their areas, for reports and tests.
std::vector<double> PieceAreas(const Mesh& m);
// Boundary edges (used by one triangle) and the loops they form.
struct Boundary {
  int edges = 0;
  std::vector<std::vector<int>> loops;  // vertex indices in order
};
Boundary FindBoundary(const Mesh& m);
double TriangleArea(const Mesh& m, std::size_t t);

}  // namespace hdrf::mesh
