#include "mesh/mesh.h"

#include <algorithm>

#include "mesh/mesh_assemble.h"
#include "mesh/mesh_impl.h"

namespace hdrf::mesh {

namespace {
template <typename V>
Mesh Extract(const volume::Volume& vol, void (*progress)(double, void*), void* user) {
  const volume::VolumeView<V> view = vol.view<V>();
  const auto& bricks = vol.bricks();
  // 1. Triangles of every cube, as edge keys, in cube order.
  std::vector<std::array<std::uint64_t, 3>> tris;
  std::uint64_t t[kMaxCubeTriangles][3];
  for (std::size_t bi = 0; bi < bricks.size(); ++bi) {
    if (progress && bi % 256 == 0) progress(0.8 * double(bi) / double(bricks.size()), user);
    const auto b = bricks[bi];
    for (int i = 0; i < 512; ++i) {
      const int nt = CubeTriangles(view, b[0] * 8 + (i & 7), b[1] * 8 + ((i >> 3) & 7), b[2] * 8 + (i >> 6), t);
      for (int k = 0; k < nt; ++k) tris.push_back({t[k][0], t[k][1], t[k][2]});
    }
  }
  // 2. One vertex per distinct edge, in key order; 3. triangles as vertex indices, facing
  // the free space.
  Mesh m = MeshFromEdgeTriangles(view, tris, /*threads=*/true);
  if (progress) progress(1.0, user);
  return m;
}
}  // namespace

Mesh ExtractMesh(const volume::Volume& vol, void (*progress)(double, void*), void* user) {
  return volume::VisitEncoding(vol.options().encoding,
                               [&](auto tag) { return Extract<decltype(tag)>(vol, progress, user); });
}

}  // namespace hdrf::mesh
