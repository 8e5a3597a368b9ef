#include "mesh/incremental_mesh.h"

#include <algorithm>
#include <array>
#include <vector>

#include "mesh/mesh_assemble.h"
#include "mesh/mesh_impl.h"

namespace hdrf::mesh {

namespace {

// The surface of one brick's 512 cubes, as Extract (mesh.cpp) builds the whole model's: the
// same cube triangles, vertices and orientation, with the vertices this brick's cubes use.
template <typename V>
Mesh MeshBrick(const volume::VolumeView<V>& view, const std::array<int, 3>& b) {
  std::vector<std::array<std::uint64_t, 3>> tris;
  std::uint64_t t[kMaxCubeTriangles][3];
  for (int i = 0; i < 512; ++i) {
    const int nt = CubeTriangles(view, b[0] * 8 + (i & 7), b[1] * 8 + ((i >> 3) & 7), b[2] * 8 + (i >> 6), t);
    for (int k = 0; k < nt; ++k) tris.push_back({t[k][0], t[k][1], t[k][2]});
  }
  if (tris.empty()) return Mesh{};
  return MeshFromEdgeTriangles(view, tris, /*threads=*/false);
}

}  // namespace

IncrementalMesher::IncrementalMesher(const volume::VolumeOptions& o) : mirror_(o) {}

std::size_t IncrementalMesher::Apply(const volume::BrickSet& changed) {
  mirror_.Store(changed);
  // The changed bricks and their neighbours that the mirror holds, each once.
  std::vector<std::uint64_t> todo;
  todo.reserve(changed.size() * 4);
  for (const auto& c : changed.coords)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
          if (volume::BrickInRange(x, y, z) && mirror_.BrickAllocated(x, y, z)) todo.push_back(volume::BrickKey(x, y, z));
        }
  std::sort(todo.begin(), todo.end());
  todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
  std::vector<Mesh> meshed(todo.size());
  volume::VisitEncoding(mirror_.options().encoding, [&](auto tag) {
    const volume::VolumeView<decltype(tag)> view = mirror_.view<decltype(tag)>();
    for (std::size_t i = 0; i < todo.size(); ++i) {
      std::array<int, 3> b;
      volume::DecodeBrickKey(todo[i], &b[0], &b[1], &b[2]);
      meshed[i] = MeshBrick(view, b);
    }
  });
  for (std::size_t i = 0; i < todo.size(); ++i) {
    if (meshed[i].triangles.empty())
      pieces_.erase(todo[i]);
    else
      pieces_[todo[i]] = std::move(meshed[i]);
  }
  return todo.size();
}

Mesh IncrementalMesher::Assemble() const {
  std::vector<std::uint64_t> keys;
  keys.reserve(pieces_.size());
  std::size_t nv = 0, nt = 0;
  for (const auto& [k, m] : pieces_) {
    keys.push_back(k);
    nv += m.position.size();
    nt += m.triangles.size();
  }
  std::sort(keys.begin(), keys.end());
  Mesh out;
  out.position.reserve(nv);
  out.normal.reserve(nv);
  out.radiance.reserve(nv);
  out.triangles.reserve(nt);
  for (const std::uint64_t k : keys) {
    const Mesh& m = pieces_.at(k);
    const auto base = std::int32_t(out.position.size());
    out.position.insert(out.position.end(), m.position.begin(), m.position.end());
    out.normal.insert(out.normal.end(), m.normal.begin(), m.normal.end());
    out.radiance.insert(out.radiance.end(), m.radiance.begin(), m.radiance.end());
    for (const auto& t : m.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return out;
}

}  // namespace hdrf::mesh
