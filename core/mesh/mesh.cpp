#include "mesh/mesh.h"

#include <cmath>
#include <unordered_map>

namespace hdrf::mesh {

namespace {
// Six tetrahedra sharing the cube's diagonal 0-7; corners numbered x + 2y + 4z.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                             {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
}  // namespace

Mesh ExtractMesh(const volume::Volume& vol, void (*progress)(double, void*), void* user) {
  Mesh m;
  const int n = vol.options().resolution;
  const float vs = vol.options().voxel_m();
  const Float3 origin = vol.origin();
  std::unordered_map<std::uint64_t, std::int32_t> edge_vertex;
  auto voxel_id = [n](int x, int y, int z) { return (std::uint64_t(z) * n + y) * n + x; };
  auto centre = [&](int x, int y, int z) {
    return origin + Float3{(x + 0.5f) * vs, (y + 0.5f) * vs, (z + 0.5f) * vs};
  };
  const auto& bricks = vol.bricks();
  for (std::size_t bi = 0; bi < bricks.size(); ++bi) {
    if (progress && bi % 256 == 0) progress(double(bi) / double(bricks.size()), user);
    const auto b = bricks[bi];
    for (int lz = 0; lz < 8; ++lz)
      for (int ly = 0; ly < 8; ++ly)
        for (int lx = 0; lx < 8; ++lx) {
          const int x = b[0] * 8 + lx, y = b[1] * 8 + ly, z = b[2] * 8 + lz;
          volume::Voxel c[8];
          int ix[8][3];
          bool ok = true, pos = false, neg = false;
          for (int k = 0; k < 8 && ok; ++k) {
            ix[k][0] = x + (k & 1);
            ix[k][1] = y + ((k >> 1) & 1);
            ix[k][2] = z + (k >> 2);
            ok = vol.Get(ix[k][0], ix[k][1], ix[k][2], &c[k]) && c[k].w > 0;
            if (ok) (c[k].tsdf < 0 ? neg : pos) = true;
          }
          if (!ok || !pos || !neg) continue;
          // Vertex on the edge between corners a and b (shared by id).
          auto vertex = [&](int a, int bb) {
            // Unique edge key: the lower voxel id and the offset (-1..1 per axis) to the other.
            int lo = a, hi = bb;
            if (voxel_id(ix[lo][0], ix[lo][1], ix[lo][2]) > voxel_id(ix[hi][0], ix[hi][1], ix[hi][2]))
              std::swap(lo, hi);
            const int code = (ix[hi][0] - ix[lo][0] + 1) + 3 * (ix[hi][1] - ix[lo][1] + 1) +
                             9 * (ix[hi][2] - ix[lo][2] + 1);
            const std::uint64_t key = voxel_id(ix[lo][0], ix[lo][1], ix[lo][2]) * 27u + std::uint64_t(code);
            const auto it = edge_vertex.find(key);
            if (it != edge_vertex.end()) return it->second;
            const float fa = c[a].tsdf, fb = c[bb].tsdf;
            const float t = fa / (fa - fb);
            const Float3 pa = centre(ix[a][0], ix[a][1], ix[a][2]);
            const Float3 pb = centre(ix[bb][0], ix[bb][1], ix[bb][2]);
            const Float3 p = pa + (pb - pa) * t;
            Float3 nrm{0, 0, 1};
            vol.Gradient(p, &nrm);
            Float3 rad{0, 0, 0};
            if (c[a].wr > 0 && c[bb].wr > 0)
              rad = c[a].radiance + (c[bb].radiance - c[a].radiance) * t;
            else if (c[a].wr > 0)
              rad = c[a].radiance;
            else if (c[bb].wr > 0)
              rad = c[bb].radiance;
            const auto id = std::int32_t(m.position.size());
            m.position.push_back(p);
            m.normal.push_back(nrm);
            m.radiance.push_back(rad);
            edge_vertex.emplace(key, id);
            return id;
          };
          auto emit = [&](std::int32_t a, std::int32_t bb, std::int32_t cc) {
            if (a == bb || bb == cc || a == cc) return;
            const Float3 gn = Cross(m.position[std::size_t(bb)] - m.position[std::size_t(a)],
                                    m.position[std::size_t(cc)] - m.position[std::size_t(a)]);
            const Float3 avg = m.normal[std::size_t(a)] + m.normal[std::size_t(bb)] + m.normal[std::size_t(cc)];
            if (Dot(gn, avg) < 0) std::swap(bb, cc);
            m.triangles.push_back({a, bb, cc});
          };
          for (const auto& tet : kTets) {
            int in[4], out[4], ni = 0, no = 0;
            for (int k : tet) (c[k].tsdf < 0 ? in[ni++] : out[no++]) = k;
            if (ni == 0 || no == 0) continue;
            if (ni == 1) {
              emit(vertex(in[0], out[0]), vertex(in[0], out[1]), vertex(in[0], out[2]));
            } else if (no == 1) {
              emit(vertex(out[0], in[0]), vertex(out[0], in[1]), vertex(out[0], in[2]));
            } else {  // 2-2: a quad
              const auto a = vertex(in[0], out[0]), bb = vertex(in[0], out[1]);
              const auto cc = vertex(in[1], out[1]), d = vertex(in[1], out[0]);
              emit(a, bb, cc);
              emit(a, cc, d);
            }
          }
        }
  }
  if (progress) progress(1.0, user);
  return m;
}

}  // namespace hdrf::mesh
