#include "mesh/mesh.h"

#include <algorithm>

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
  // 2. One vertex per distinct edge, in key order.
  std::vector<std::uint64_t> keys;
  keys.reserve(tris.size() * 3);
  for (const auto& tr : tris) keys.insert(keys.end(), tr.begin(), tr.end());
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  Mesh m;
  m.position.resize(keys.size());
  m.normal.resize(keys.size());
  m.radiance.resize(keys.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(keys.size()); ++i)
    EdgeVertex(view, keys[std::size_t(i)], &m.position[std::size_t(i)], &m.normal[std::size_t(i)],
               &m.radiance[std::size_t(i)]);
  // 3. Triangles as vertex indices, facing the free space.
  m.triangles.resize(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    std::int32_t* idx = m.triangles[i].data();
    for (int k = 0; k < 3; ++k)
      idx[k] = std::int32_t(std::lower_bound(keys.begin(), keys.end(), tris[i][std::size_t(k)]) - keys.begin());
    OrientTriangle(m.position.data(), m.normal.data(), idx);
  }
  if (progress) progress(1.0, user);
  return m;
}
}  // namespace

Mesh ExtractMesh(const volume::Volume& vol, void (*progress)(double, void*), void* user) {
  return volume::VisitEncoding(vol.options().encoding,
                               [&](auto tag) { return Extract<decltype(tag)>(vol, progress, user); });
}

}  // namespace hdrf::mesh
