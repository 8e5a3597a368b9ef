// The last two steps of surface extraction, shared by the whole-model mesher (mesh.cpp) and
// the per-brick one (incremental_mesh.cpp), host code: from the cubes' triangles as edge
// keys, one vertex per distinct edge (in key order, EdgeVertex), then the triangles as vertex
// indices, each facing the free space (OrientTriangle).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/mesh_impl.h"

namespace hdrf::mesh {

// `threads`: the vertices computed on the OpenMP threads (the whole model), or on the
// caller's thread alone (one brick, on a thread that must not take the scan's cores).
// `step`: the lattice the keys name (CubeTriangles).
template <typename V>
Mesh MeshFromEdgeTriangles(const volume::VolumeView<V>& view, const std::vector<std::array<std::uint64_t, 3>>& tris,
                           bool threads, int step = 1) {
  std::vector<std::uint64_t> keys;
  keys.reserve(tris.size() * 3);
  for (const auto& tr : tris) keys.insert(keys.end(), tr.begin(), tr.end());
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  Mesh m;
  m.position.resize(keys.size());
  m.normal.resize(keys.size());
  m.radiance.resize(keys.size());
#pragma omp parallel for schedule(static) if (threads)
  for (long i = 0; i < long(keys.size()); ++i)
    EdgeVertex(view, keys[std::size_t(i)], &m.position[std::size_t(i)], &m.normal[std::size_t(i)],
               &m.radiance[std::size_t(i)], step);
  m.triangles.resize(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    std::int32_t* idx = m.triangles[i].data();
    for (int k = 0; k < 3; ++k)
      idx[k] = std::int32_t(std::lower_bound(keys.begin(), keys.end(), tris[i][std::size_t(k)]) - keys.begin());
    OrientTriangle(m.position.data(), m.normal.data(), idx);
  }
  return m;
}

}  // namespace hdrf::mesh
