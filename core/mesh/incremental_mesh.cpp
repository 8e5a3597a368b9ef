#include "mesh/incremental_mesh.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "common/error.h"
#include "mesh/mesh_assemble.h"
#include "mesh/mesh_impl.h"

namespace hdrf::mesh {

namespace {

// The surface of one brick's cubes at a step (512 cubes at step 1, 64 at step 2, 8 at 4), as Extract
// (mesh.cpp) builds the whole model's at step 1: the same cube triangles, vertices and
// orientation, with the vertices this brick's cubes use.
template <typename V>
Mesh MeshBrick(const volume::VolumeView<V>& view, const std::array<int, 3>& b, int step) {
  std::vector<std::array<std::uint64_t, 3>> tris;
  std::uint64_t t[kMaxCubeTriangles][3];
  const int n = volume::kBrick / step;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int nt = CubeTriangles(view, b[0] * volume::kBrick + i * step, b[1] * volume::kBrick + j * step,
                                     b[2] * volume::kBrick + k * step, t, step);
        for (int q = 0; q < nt; ++q) tris.push_back({t[q][0], t[q][1], t[q][2]});
      }
  if (tris.empty()) return Mesh{};
  return MeshFromEdgeTriangles(view, tris, /*threads=*/false, step);
}

void CheckStep(int step) {
  if (step != 1 && step != 2 && step != 4)
    throw Error("incremental mesher: step " + std::to_string(step) + " (1, 2 or 4)");
}

std::size_t LevelIndex(int step) {
  CheckStep(step);
  return step == 4 ? 2 : std::size_t(step - 1);
}

}  // namespace

IncrementalMesher::IncrementalMesher(const volume::VolumeOptions& o) : mirror_(o) {}

const IncrementalMesher::Level& IncrementalMesher::level(int step) const { return levels_[LevelIndex(step)]; }
IncrementalMesher::Level& IncrementalMesher::level(int step) { return levels_[LevelIndex(step)]; }

std::size_t IncrementalMesher::Apply(const volume::BrickSet& changed, int step, int refresh_after) {
  Level& l = level(step);
  mirror_.Store(changed);
  // The changed bricks and their neighbours that the mirror holds: stale at every step.
  for (const auto& c : changed.coords)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
          if (!volume::BrickInRange(x, y, z) || !mirror_.BrickAllocated(x, y, z)) continue;
          for (Level& each : levels_) each.stale.insert(volume::BrickKey(x, y, z));
        }
  ++l.calls;
  std::vector<std::uint64_t> todo;
  todo.reserve(l.stale.size());
  for (auto it = l.stale.begin(); it != l.stale.end();) {
    if (refresh_after > 0 && l.pieces.count(*it)) {
      const auto at = l.meshed_at.find(*it);
      if (at != l.meshed_at.end() && l.calls - at->second < std::uint32_t(refresh_after)) {
        ++it;  // its surface is shown and was meshed lately: waits
        continue;
      }
    }
    todo.push_back(*it);
    it = l.stale.erase(it);
  }
  std::sort(todo.begin(), todo.end());
  for (const std::uint64_t k : todo) l.meshed_at[k] = l.calls;
  std::vector<Mesh> meshed(todo.size());
  volume::VisitEncoding(mirror_.options().encoding, [&](auto tag) {
    const volume::VolumeView<decltype(tag)> view = mirror_.view<decltype(tag)>();
    for (std::size_t i = 0; i < todo.size(); ++i) {
      std::array<int, 3> b;
      volume::DecodeBrickKey(todo[i], &b[0], &b[1], &b[2]);
      meshed[i] = MeshBrick(view, b, step);
    }
  });
  for (std::size_t i = 0; i < todo.size(); ++i) {
    if (meshed[i].triangles.empty())
      l.pieces.erase(todo[i]);
    else
      l.pieces[todo[i]] = std::move(meshed[i]);
  }
  return todo.size();
}

Mesh IncrementalMesher::Assemble(int step) const {
  const auto& pieces = level(step).pieces;
  std::vector<std::uint64_t> keys;
  keys.reserve(pieces.size());
  std::size_t nv = 0, nt = 0;
  for (const auto& [k, m] : pieces) {
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
    const Mesh& m = pieces.at(k);
    const auto base = std::int32_t(out.position.size());
    out.position.insert(out.position.end(), m.position.begin(), m.position.end());
    out.normal.insert(out.normal.end(), m.normal.begin(), m.normal.end());
    out.radiance.insert(out.radiance.end(), m.radiance.begin(), m.radiance.end());
    for (const auto& t : m.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return out;
}

}  // namespace hdrf::mesh
