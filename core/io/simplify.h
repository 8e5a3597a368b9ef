// Simplification to a triangle budget (meshoptimizer's edge collapse, which keeps a subset
// of the original vertices: their normals, radiance and flags carry over unchanged).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace hdrf::io {

struct SimplifyResult {
  mesh::Mesh mesh;
  std::vector<std::int32_t> source;  // per output vertex: its index in the input
  double error_m = 0;                // largest deviation the simplifier reports, metres
};

// At most `target_triangles` (it may stop above: when no collapse stays within
// `max_error_m`, or at boundaries, which are kept). Throws SettingError for a target of 0.
SimplifyResult Simplify(const mesh::Mesh& in, std::size_t target_triangles, double max_error_m = 0.01);

}  // namespace hdrf::io
