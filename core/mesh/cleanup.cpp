#include "mesh/cleanup.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <unordered_map>

#include "common/error.h"

namespace hdrf::mesh {

void CleanOptions::Check() const {
  if (!(weld_tolerance >= 0 && weld_tolerance < 0.01)) throw SettingError("weld", "the weld tolerance must be within [0, 0.01) m");
  if (!(min_piece_area >= 0)) throw SettingError("min-piece-area", "cannot be negative");
  if (!(max_hole_perimeter >= 0)) throw SettingError("max-hole", "cannot be negative");
  if (crop && !(crop->min.x < crop->max.x && crop->min.y < crop->max.y && crop->min.z < crop->max.z))
    throw SettingError("crop", "the box's minimum must be below its maximum on every axis");
}

namespace {

bool HasRadiance(Float3 c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && Luminance(c) > 0;
}

struct UnionFind {
  std::vector<int> p;
  explicit UnionFind(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0); }
  int Find(int a) {
    while (p[std::size_t(a)] != a) a = p[std::size_t(a)] = p[std::size_t(p[std::size_t(a)])];
    return a;
  }
  void Join(int a, int b) { p[std::size_t(Find(a))] = Find(b); }
};

double Area(Float3 a, Float3 b, Float3 c) { return 0.5 * double(Length(Cross(b - a, c - a))); }

// Keeps the vertices `keep` marks, in order, and remaps the triangles (dropping any that
// touch a removed vertex).
void Compact(Mesh& m, std::vector<std::uint8_t>& flags, std::vector<std::int32_t>& source, const std::vector<char>& keep) {
  std::vector<std::int32_t> map(m.position.size(), -1);
  Mesh out;
  std::vector<std::uint8_t> out_flags;
  std::vector<std::int32_t> out_source;
  for (std::size_t v = 0; v < m.position.size(); ++v) {
    if (!keep[v]) continue;
    map[v] = std::int32_t(out.position.size());
    out.position.push_back(m.position[v]);
    if (v < m.normal.size()) out.normal.push_back(m.normal[v]);
    if (v < m.radiance.size()) out.radiance.push_back(m.radiance[v]);
    out_flags.push_back(flags[v]);
    out_source.push_back(source[v]);
  }
  for (const auto& t : m.triangles) {
    const std::array<std::int32_t, 3> r = {map[std::size_t(t[0])], map[std::size_t(t[1])], map[std::size_t(t[2])]};
    if (r[0] >= 0 && r[1] >= 0 && r[2] >= 0) out.triangles.push_back(r);
  }
  m = std::move(out);
  flags = std::move(out_flags);
  source = std::move(out_source);
}

std::vector<char> Referenced(const Mesh& m) {
  std::vector<char> used(m.position.size(), 0);
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) used[std::size_t(t[std::size_t(k)])] = 1;
  return used;
}

}  // namespace

double TriangleArea(const Mesh& m, std::size_t t) {
  const auto& tri = m.triangles[t];
  return Area(m.position[std::size_t(tri[0])], m.position[std::size_t(tri[1])], m.position[std::size_t(tri[2])]);
}

std::vector<double> PieceAreas(const Mesh& m) {
  UnionFind uf(m.position.size());
  for (const auto& t : m.triangles) uf.Join(t[0], t[1]), uf.Join(t[1], t[2]);
  std::unordered_map<int, double> area;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) area[uf.Find(m.triangles[t][0])] += TriangleArea(m, t);
  std::vector<double> out;
  for (const auto& [root, a] : area) out.push_back(a);
  std::sort(out.rbegin(), out.rend());
  return out;
}

Boundary FindBoundary(const Mesh& m) {
  // Undirected edge -> uses; the boundary's directed edges as their triangle orients them.
  std::unordered_map<std::uint64_t, int> uses;
  auto key = [](std::int32_t a, std::int32_t b) {
    return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
  };
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++uses[key(t[std::size_t(k)], t[std::size_t((k + 1) % 3)])];
  std::unordered_multimap<std::int32_t, std::int32_t> next;
  Boundary b;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[std::size_t(k)], c = t[std::size_t((k + 1) % 3)];
      if (uses[key(a, c)] == 1) next.emplace(a, c), ++b.edges;
    }
  // Chain into loops (at a vertex where several boundary edges leave, any unused one).
  while (!next.empty()) {
    auto it = next.begin();
    const std::int32_t start = it->first;
    std::vector<int> loop = {start};
    std::int32_t cur = it->second;
    next.erase(it);
    for (std::size_t steps = 0; cur != start && steps < m.position.size(); ++steps) {
      loop.push_back(cur);
      auto nx = next.find(cur);
      if (nx == next.end()) break;  // an open chain (non-manifold): not a loop
      cur = nx->second;
      next.erase(nx);
    }
    if (cur == start && loop.size() >= 3) b.loops.push_back(std::move(loop));
  }
  return b;
}

namespace {

// Crop: triangles with a vertex outside the box are removed.
void Crop(Mesh& m, const Box& b, CleanReport& rep) {
  auto inside = [&](std::int32_t v) {
    const Float3 p = m.position[std::size_t(v)];
    return p.x >= b.min.x && p.y >= b.min.y && p.z >= b.min.z && p.x <= b.max.x && p.y <= b.max.y && p.z <= b.max.z;
  };
  std::vector<std::array<std::int32_t, 3>> kept;
  for (const auto& t : m.triangles)
    if (inside(t[0]) && inside(t[1]) && inside(t[2])) kept.push_back(t);
  rep.cropped = int(m.triangles.size() - kept.size());
  m.triangles = std::move(kept);
}

// Weld: a hash grid of cells the tolerance wide; a vertex joins the first earlier vertex
// within the tolerance in its own or a neighbouring cell.
void Weld(Mesh& m, double tolerance, CleanReport& rep) {
  const double cell = tolerance;
  auto cell_of = [&](Float3 p) {
    return std::array<std::int64_t, 3>{std::int64_t(std::floor(p.x / cell)), std::int64_t(std::floor(p.y / cell)),
                                       std::int64_t(std::floor(p.z / cell))};
  };
  auto hash = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return std::uint64_t(x) * 73856093ull ^ std::uint64_t(y) * 19349663ull ^ std::uint64_t(z) * 83492791ull;
  };
  std::unordered_multimap<std::uint64_t, std::int32_t> grid;
  std::vector<std::int32_t> rep_of(m.position.size());
  const double tol2 = tolerance * tolerance;
  for (std::size_t v = 0; v < m.position.size(); ++v) {
    const Float3 p = m.position[v];
    const auto c = cell_of(p);
    std::int32_t found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          auto range = grid.equal_range(hash(c[0] + dx, c[1] + dy, c[2] + dz));
          for (auto it = range.first; it != range.second; ++it) {
            const Float3 d = m.position[std::size_t(it->second)] - p;
            if (double(Dot(d, d)) <= tol2) {
              found = it->second;
              break;
            }
          }
        }
    if (found >= 0) {
      rep_of[v] = found;
      ++rep.welded;
      // Keep the radiance where the kept vertex has none.
      if (!HasRadiance(m.radiance[std::size_t(found)]) && HasRadiance(m.radiance[v]))
        m.radiance[std::size_t(found)] = m.radiance[v];
    } else {
      rep_of[v] = std::int32_t(v);
      grid.emplace(hash(c[0], c[1], c[2]), std::int32_t(v));
    }
  }
  for (auto& t : m.triangles)
    for (auto& i : t) i = rep_of[std::size_t(i)];
}

// Degenerate and duplicate triangles.
void DropDegenerate(Mesh& m, CleanReport& rep) {
  std::vector<std::array<std::int32_t, 3>> kept;
  std::set<std::array<std::int32_t, 3>> seen;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || !(TriangleArea(m, t) > 1e-12)) {
      ++rep.degenerate_removed;
      continue;
    }
    std::array<std::int32_t, 3> s = tri;
    std::sort(s.begin(), s.end());
    if (!seen.insert(s).second) {
      ++rep.duplicate_removed;
      continue;
    }
    kept.push_back(tri);
  }
  m.triangles = std::move(kept);
}

// Pieces: drop the small ones and those that never got any radiance.
void DropPieces(Mesh& m, double min_area, CleanReport& rep) {
  UnionFind uf(m.position.size());
  for (const auto& t : m.triangles) uf.Join(t[0], t[1]), uf.Join(t[1], t[2]);
  std::unordered_map<int, double> area;
  std::unordered_map<int, bool> lit;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const int root = uf.Find(m.triangles[t][0]);
    area[root] += TriangleArea(m, t);
    for (int k = 0; k < 3; ++k) lit[root] = lit[root] || HasRadiance(m.radiance[std::size_t(m.triangles[t][std::size_t(k)])]);
  }
  std::vector<std::array<std::int32_t, 3>> kept;
  for (const auto& t : m.triangles) {
    const int root = uf.Find(t[0]);
    if (area[root] >= min_area && lit[root]) kept.push_back(t);
  }
  for (const auto& [root, a] : area) (a >= min_area && lit[root] ? rep.pieces_kept : rep.pieces_removed) += 1;
  m.triangles = std::move(kept);
}

// Holes: each boundary loop up to the perimeter closed by a fan around its centroid.
void FillHoles(Mesh& m, double max_perimeter, CleanMesh& r) {
  CleanReport& rep = r.report;
  std::vector<std::uint8_t>& flags = r.radiance_filled;
  const Boundary b = FindBoundary(m);
  for (const auto& loop : b.loops) {
    double perimeter = 0;
    for (std::size_t i = 0; i < loop.size(); ++i)
      perimeter += Length(m.position[std::size_t(loop[(i + 1) % loop.size()])] - m.position[std::size_t(loop[i])]);
    if (perimeter > max_perimeter) {
      ++rep.holes_left;
      continue;
    }
    Float3 c{0, 0, 0}, n{0, 0, 0}, rad{0, 0, 0};
    int lit = 0;
    for (int v : loop) {
      c += m.position[std::size_t(v)];
      n += m.normal[std::size_t(v)];
      if (HasRadiance(m.radiance[std::size_t(v)])) rad += m.radiance[std::size_t(v)], ++lit;
    }
    const std::int32_t centre = std::int32_t(m.position.size());
    m.position.push_back(c / float(loop.size()));
    m.normal.push_back(Length(n) > 0 ? Normalized(n) : Float3{0, 0, 0});
    m.radiance.push_back(lit ? rad / float(lit) : Float3{0, 0, 0});
    flags.push_back(1);
    r.source.push_back(-1);
    // The loop runs along the boundary as its triangles orient it; the fan runs the other way.
    for (std::size_t i = 0; i < loop.size(); ++i)
      m.triangles.push_back({std::int32_t(loop[(i + 1) % loop.size()]), std::int32_t(loop[i]), centre});
    ++rep.holes_filled;
  }
}

// Radiance: vertices without it take the mean of their neighbours that have it, ring by
// ring outwards from the seen surface.
void FillRadiance(Mesh& m, const std::vector<char>& keep, CleanMesh& r) {
  CleanReport& rep = r.report;
  std::vector<std::uint8_t>& flags = r.radiance_filled;
  std::vector<std::vector<std::int32_t>> adj(m.position.size());
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      adj[std::size_t(t[std::size_t(k)])].push_back(t[std::size_t((k + 1) % 3)]);
      adj[std::size_t(t[std::size_t(k)])].push_back(t[std::size_t((k + 2) % 3)]);
    }
  std::vector<char> has(m.position.size());
  for (std::size_t v = 0; v < m.position.size(); ++v) has[v] = HasRadiance(m.radiance[v]);
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::pair<std::size_t, Float3>> wave;
    for (std::size_t v = 0; v < m.position.size(); ++v) {
      if (has[v] || !keep[v]) continue;
      Float3 s{0, 0, 0};
      int n = 0;
      for (std::int32_t u : adj[v])
        if (has[std::size_t(u)]) s += m.radiance[std::size_t(u)], ++n;
      if (n) wave.emplace_back(v, s / float(n));
    }
    for (const auto& [v, c] : wave) {
      m.radiance[v] = c;
      has[v] = 1;
      if (!flags[v]) ++rep.radiance_filled;
      flags[v] = 1;
      changed = true;
    }
  }
  for (std::size_t v = 0; v < m.position.size(); ++v) rep.radiance_missing += keep[v] && !has[v];
}

}  // namespace

CleanMesh Clean(const Mesh& in, const CleanOptions& o) {
  o.Check();
  CleanMesh r;
  Mesh& m = r.mesh;
  m = in;
  if (m.radiance.size() != m.position.size()) m.radiance.assign(m.position.size(), Float3{0, 0, 0});
  if (m.normal.size() != m.position.size()) m.normal.assign(m.position.size(), Float3{0, 0, 0});
  std::vector<std::uint8_t>& flags = r.radiance_filled;
  flags.assign(m.position.size(), 0);
  r.source.resize(m.position.size());
  std::iota(r.source.begin(), r.source.end(), 0);
  CleanReport& rep = r.report;

  if (o.crop) Crop(m, *o.crop, rep);
  if (o.weld_tolerance > 0) Weld(m, o.weld_tolerance, rep);
  DropDegenerate(m, rep);
  DropPieces(m, o.min_piece_area, rep);
  if (o.max_hole_perimeter > 0) FillHoles(m, o.max_hole_perimeter, r);
  std::vector<char> keep = Referenced(m);
  if (o.fill_radiance) FillRadiance(m, keep, r);
  Compact(m, flags, r.source, keep);
  return r;
}

}  // namespace hdrf::mesh
