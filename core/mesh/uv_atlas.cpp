#include "mesh/uv_atlas.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "common/error.h"
#include "mesh/raster.h"

namespace hdrf::mesh {

void AtlasOptions::Check() const {
  if (fit_size <= 0 && !(texel_m >= 1e-4 && texel_m <= 1.0))
    throw SettingError("texel size", "must be between 0.1 mm and 1 m per texel, got " + std::to_string(texel_m * 1000) + " mm");
  if (fit_size < 0 || fit_size > max_size)
    throw SettingError("texture size", "must be between 16 and " + std::to_string(max_size) + ", got " + std::to_string(fit_size));
  if (fit_size > 0 && fit_size < 16)
    throw SettingError("texture size", "must be at least 16 texels, got " + std::to_string(fit_size));
  if (padding < 0 || padding > 16) throw SettingError("padding", "must be 0 to 16 texels, got " + std::to_string(padding));
  if (!(chart_angle_deg >= 5 && chart_angle_deg <= 80))
    throw SettingError("chart angle", "must be 5 to 80 degrees, got " + std::to_string(chart_angle_deg));
  if (max_size < 16 || max_size > 32768) throw SettingError("max texture size", "must be 16 to 32768");
}

Float2 Atlas::UvTopLeft(std::size_t v) const {
  return {(texel[v].x + 0.5f) / float(width), (texel[v].y + 0.5f) / float(height)};
}
Float2 Atlas::UvBottomLeft(std::size_t v) const {
  const Float2 t = UvTopLeft(v);
  return {t.x, 1.0f - t.y};
}

double Atlas::Utilisation() const {
  if (width == 0 || height == 0) return 0;
  long covered = 0;
  for (const auto& t : mesh.triangles)
    RasterizeTriangle(texel[std::size_t(t[0])], texel[std::size_t(t[1])], texel[std::size_t(t[2])], width, height,
                      [&](int, int, float, float, float) { ++covered; });
  return double(covered) / (double(width) * double(height));
}

long CountOverlappingTexels(const Atlas& a) {
  if (a.width == 0) return 0;
  std::vector<std::uint8_t> count(std::size_t(a.width) * std::size_t(a.height), 0);
  long over = 0;
  for (const auto& t : a.mesh.triangles)
    RasterizeTriangle(a.texel[std::size_t(t[0])], a.texel[std::size_t(t[1])], a.texel[std::size_t(t[2])], a.width,
                      a.height, [&](int x, int y, float, float, float) {
                        std::uint8_t& c = count[std::size_t(y) * std::size_t(a.width) + std::size_t(x)];
                        if (c == 1) ++over;
                        if (c < 255) ++c;
                      });
  return over;
}

namespace {

struct Face {
  Float3 geometric;  // unit, oriented like the smoothed normal on average
  Float3 smooth;     // unit
  double area = 0;
};

struct ChartBuild {
  std::vector<int> faces;
  Float3 axis{0, 0, 1};
  // Per local vertex: the input vertex and its 2-D position in metres (principal axes).
  std::vector<int> verts;
  std::vector<Eigen::Vector2d> uv_m;
  Eigen::Vector2d lo{0, 0}, hi{0, 0};
  int rect_w = 0, rect_h = 0, x0 = 0, y0 = 0;
};

class Builder {
 public:
  Builder(const Mesh& m, const AtlasOptions& o) : m_(m), o_(o) {
    const std::size_t nf = m.triangles.size();
    faces_.resize(nf);
    double orientation = 0;
    const bool has_normals = m.normal.size() == m.position.size();
    for (std::size_t f = 0; f < nf; ++f) {
      const auto& t = m.triangles[f];
      const Float3 p0 = m.position[std::size_t(t[0])], p1 = m.position[std::size_t(t[1])], p2 = m.position[std::size_t(t[2])];
      const Float3 c = Cross(p1 - p0, p2 - p0);
      const float len = Length(c);
      Face& F = faces_[f];
      F.area = 0.5 * double(len);
      F.geometric = len > 0 ? c / len : Float3{0, 0, 0};
      Float3 s = F.geometric;
      if (has_normals) {
        const Float3 n = m.normal[std::size_t(t[0])] + m.normal[std::size_t(t[1])] + m.normal[std::size_t(t[2])];
        if (Length(n) > 1e-6f) s = Normalized(n);
      }
      F.smooth = s;
      orientation += double(Dot(F.geometric, s)) * F.area;
    }
    // The winding may be opposite to the normals (into free space): align them.
    if (has_normals && orientation < 0)
      for (Face& F : faces_) F.geometric = -F.geometric;
    if (!has_normals)
      for (Face& F : faces_) F.smooth = F.geometric;
    // Edge adjacency (manifold edges only: an edge of three or more triangles separates charts).
    struct E {
      std::int64_t key;
      int face;
    };
    std::vector<E> edges;
    edges.reserve(nf * 3);
    const std::int64_t nv = std::int64_t(m.position.size());
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        std::int64_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
        if (a > b) std::swap(a, b);
        edges.push_back({a * nv + b, int(f)});
      }
    std::sort(edges.begin(), edges.end(), [](const E& x, const E& y) { return x.key < y.key; });
    adj_start_.assign(nf + 1, 0);
    std::vector<std::pair<int, int>> pairs;
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].key == edges[i].key) ++j;
      if (j - i == 2) pairs.push_back({edges[i].face, edges[i + 1].face});
      i = j;
    }
    for (const auto& p : pairs) ++adj_start_[std::size_t(p.first) + 1], ++adj_start_[std::size_t(p.second) + 1];
    std::partial_sum(adj_start_.begin(), adj_start_.end(), adj_start_.begin());
    adj_.resize(adj_start_.back());
    std::vector<int> fill(adj_start_.begin(), adj_start_.end() - 1);
    for (const auto& p : pairs) {
      adj_[std::size_t(fill[std::size_t(p.first)]++)] = p.second;
      adj_[std::size_t(fill[std::size_t(p.second)]++)] = p.first;
    }
    member_.assign(nf, -1);
    vert_stamp_.assign(m.position.size(), -1);
    vert_local_.assign(m.position.size(), -1);
  }

  // Splits `faces` (all carrying membership token `token`) into charts at `angle_deg`.
  void Segment(const std::vector<int>& faces, double angle_deg, std::vector<ChartBuild>& out) {
    const int token = next_token_++;
    for (int f : faces) member_[std::size_t(f)] = token;
    const float cos_max = float(std::cos(angle_deg * M_PI / 180.0));
    std::vector<int> queue;
    for (int seed : faces) {
      if (member_[std::size_t(seed)] != token) continue;
      // Grow from the seed's normal, then once more from the chart's mean normal.
      ChartBuild c;
      Float3 axis = faces_[std::size_t(seed)].smooth;
      for (int pass = 0; pass < 2; ++pass) {
        const int grow = next_token_++;
        c.faces.clear();
        queue.assign(1, seed);
        member_[std::size_t(seed)] = grow;
        while (!queue.empty()) {
          const int f = queue.back();
          queue.pop_back();
          c.faces.push_back(f);
          for (int k = adj_start_[std::size_t(f)]; k < adj_start_[std::size_t(f) + 1]; ++k) {
            const int g = adj_[std::size_t(k)];
            if (member_[std::size_t(g)] != token) continue;
            const Face& G = faces_[std::size_t(g)];
            if (Dot(G.smooth, axis) < cos_max || Dot(G.geometric, axis) < 0.2f) continue;
            member_[std::size_t(g)] = grow;
            queue.push_back(g);
          }
        }
        Float3 mean{0, 0, 0};
        for (int f : c.faces) mean += faces_[std::size_t(f)].smooth * float(faces_[std::size_t(f)].area);
        const Float3 refined = Length(mean) > 0 ? Normalized(mean) : axis;
        if (pass == 0) {
          for (int f : c.faces) member_[std::size_t(f)] = token;  // release for the second growth
          const Face& S = faces_[std::size_t(seed)];
          if (Dot(S.smooth, refined) >= cos_max && Dot(S.geometric, refined) >= 0.2f) axis = refined;
        }
      }
      c.axis = axis;
      for (int f : c.faces) member_[std::size_t(f)] = -2;  // taken
      out.push_back(std::move(c));
    }
  }

  // Local vertices, 2-D coordinates on the principal axes (metres).
  void Project(ChartBuild& c) {
    const int stamp = next_token_++;
    c.verts.clear();
    for (int f : c.faces)
      for (int k = 0; k < 3; ++k) {
        const int v = m_.triangles[std::size_t(f)][k];
        if (vert_stamp_[std::size_t(v)] == stamp) continue;
        vert_stamp_[std::size_t(v)] = stamp;
        vert_local_[std::size_t(v)] = int(c.verts.size());
        c.verts.push_back(v);
      }
    const Eigen::Vector3d n(c.axis.x, c.axis.y, c.axis.z);
    const Eigen::Vector3d helper = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d e1 = n.cross(helper).normalized(), e2 = n.cross(e1);
    c.uv_m.resize(c.verts.size());
    Eigen::Vector2d mean(0, 0);
    for (std::size_t i = 0; i < c.verts.size(); ++i) {
      const Float3 p = m_.position[std::size_t(c.verts[i])];
      const Eigen::Vector3d q(p.x, p.y, p.z);
      c.uv_m[i] = {q.dot(e1), q.dot(e2)};
      mean += c.uv_m[i];
    }
    mean /= double(std::max<std::size_t>(1, c.verts.size()));
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const auto& q : c.uv_m) cov += (q - mean) * (q - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
    Eigen::Matrix2d R = es.eigenvectors().transpose();  // rows: principal axes (smallest first)
    if (R.determinant() < 0) R.row(0) *= -1;            // a rotation: the winding is kept
    c.lo = {1e300, 1e300};
    c.hi = {-1e300, -1e300};
    for (auto& q : c.uv_m) {
      q = R * (q - mean);
      c.lo = c.lo.cwiseMin(q);
      c.hi = c.hi.cwiseMax(q);
    }
  }

  // Texel positions of the chart's local vertices at a density, relative to its content origin.
  Float2 LocalTexel(const ChartBuild& c, std::size_t i, double texel_m) const {
    return {float((c.uv_m[i].x() - c.lo.x()) / texel_m), float((c.uv_m[i].y() - c.lo.y()) / texel_m)};
  }

  bool Overlaps(ChartBuild& c, double texel_m) {
    const double w = (c.hi.x() - c.lo.x()) / texel_m, h = (c.hi.y() - c.lo.y()) / texel_m;
    const int W = int(std::ceil(w)) + 1, H = int(std::ceil(h)) + 1;
    grid_.assign(std::size_t(W) * std::size_t(H), 0);
    bool overlap = false;
    for (int f : c.faces) {
      const auto& t = m_.triangles[std::size_t(f)];
      const Float2 a = LocalTexel(c, std::size_t(vert_local_[std::size_t(t[0])]), texel_m);
      const Float2 b = LocalTexel(c, std::size_t(vert_local_[std::size_t(t[1])]), texel_m);
      const Float2 d = LocalTexel(c, std::size_t(vert_local_[std::size_t(t[2])]), texel_m);
      RasterizeTriangle(a, b, d, W, H, [&](int x, int y, float, float, float) {
        std::uint8_t& g = grid_[std::size_t(y) * std::size_t(W) + std::size_t(x)];
        if (g) overlap = true;
        g = 1;
      });
      if (overlap) return true;
    }
    return false;
  }

  const Mesh& m_;
  const AtlasOptions& o_;
  std::vector<Face> faces_;
  std::vector<int> adj_start_, adj_;
  std::vector<int> member_, vert_stamp_, vert_local_;
  std::vector<std::uint8_t> grid_;
  int next_token_ = 0;
};

// Shelf packing of the charts' rectangles at a density; returns the atlas size.
std::pair<int, int> Pack(std::vector<ChartBuild>& charts, double texel_m, int padding) {
  double total = 0;
  int widest = 0;
  for (ChartBuild& c : charts) {
    c.rect_w = int(std::ceil((c.hi.x() - c.lo.x()) / texel_m)) + 1 + 2 * padding;
    c.rect_h = int(std::ceil((c.hi.y() - c.lo.y()) / texel_m)) + 1 + 2 * padding;
    total += double(c.rect_w) * double(c.rect_h);
    widest = std::max(widest, c.rect_w);
  }
  std::vector<std::size_t> order(charts.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return charts[a].rect_h != charts[b].rect_h ? charts[a].rect_h > charts[b].rect_h : charts[a].rect_w > charts[b].rect_w;
  });
  const int W = std::max(widest, int(std::ceil(std::sqrt(total * 1.08))));
  int x = 0, y = 0, shelf = 0, used_w = 0;
  for (std::size_t i : order) {
    ChartBuild& c = charts[i];
    if (x + c.rect_w > W) {
      y += shelf;
      x = 0;
      shelf = 0;
    }
    c.x0 = x;
    c.y0 = y;
    x += c.rect_w;
    used_w = std::max(used_w, x);
    shelf = std::max(shelf, c.rect_h);
  }
  const int H = y + shelf;
  const auto round4 = [](int v) { return (v + 3) / 4 * 4; };
  return {round4(std::max(used_w, 1)), round4(std::max(H, 1))};
}

}  // namespace

Atlas BuildAtlas(const Mesh& m, const AtlasOptions& o, const std::function<bool(double)>& progress) {
  o.Check();
  Atlas out;
  out.padding = o.padding;
  if (m.triangles.empty()) return out;
  const auto tick = [&](double f) {
    if (progress && !progress(f)) throw Cancelled();
  };
  Builder b(m, o);
  double surface = 0;
  for (const Face& f : b.faces_) surface += f.area;
  // The density: as asked, or a first guess for the texture size (refined after packing).
  double texel_m = o.texel_m;
  if (o.fit_size > 0) texel_m = std::sqrt(std::max(surface, 1e-8) / (double(o.fit_size) * double(o.fit_size) * 0.55));
  // A density that cannot fit even with perfect packing is refused before any work.
  const auto refuse = [&](double need_m, const std::string& size) {
    throw SettingError("texel size", std::to_string(texel_m * 1000).substr(0, 5) + " mm per texel needs " + size +
                                         " (the limit is " + std::to_string(o.max_size) + "x" + std::to_string(o.max_size) +
                                         "); use about " + std::to_string(need_m * 1000).substr(0, 5) +
                                         " mm or more, or a texture size");
  };
  if (surface / (texel_m * texel_m) > double(o.max_size) * double(o.max_size))
    refuse(std::sqrt(surface / 0.6) / double(o.max_size),
           "more than " + std::to_string(long(surface / (texel_m * texel_m) / 1e6)) + " million texels");
  // Faces without area (left by a mesh that was not cleaned) belong to no chart: they keep
  // UVs of a neighbouring vertex (never rasterised). Everything else is segmented.
  std::vector<int> all;
  all.reserve(m.triangles.size());
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
    if (b.faces_[f].area > 0) all.push_back(int(f));
  std::vector<ChartBuild> pending, charts;
  b.Segment(all, o.chart_angle_deg, pending);
  tick(0.3);
  // Overlap checks; overlapping charts are segmented again, tighter.
  std::vector<double> angle(pending.size(), o.chart_angle_deg);
  std::size_t done_faces = 0;
  while (!pending.empty()) {
    ChartBuild c = std::move(pending.back());
    pending.pop_back();
    const double a = angle.back();
    angle.pop_back();
    b.Project(c);
    if (c.faces.size() > 1 && b.Overlaps(c, texel_m)) {
      ++out.overlap_splits;
      std::vector<ChartBuild> parts;
      if (a * 0.6 >= 3) {
        b.Segment(c.faces, a * 0.6, parts);
      } else {
        for (int f : c.faces) {
          ChartBuild single;
          single.faces = {f};
          single.axis = b.faces_[std::size_t(f)].geometric;
          parts.push_back(std::move(single));
        }
      }
      for (ChartBuild& p : parts) {
        pending.push_back(std::move(p));
        angle.push_back(a * 0.6);
      }
      continue;
    }
    done_faces += c.faces.size();
    charts.push_back(std::move(c));
    if (charts.size() % 256 == 0) tick(0.3 + 0.5 * double(done_faces) / double(std::max<std::size_t>(1, all.size())));
  }
  // Pack; for a texture size, scale the density until the atlas fits (and nearly fills) it.
  auto [W, H] = Pack(charts, texel_m, o.padding);
  if (o.fit_size > 0) {
    for (int it = 0; it < 12; ++it) {
      const double over = double(std::max(W, H)) / double(o.fit_size);
      if (over <= 1.0 && over > 0.97) break;
      texel_m *= over <= 1.0 ? std::max(over, 0.5) * 1.002 : over * 1.01;
      std::tie(W, H) = Pack(charts, texel_m, o.padding);
    }
    while (std::max(W, H) > o.fit_size) {
      texel_m *= 1.02;
      std::tie(W, H) = Pack(charts, texel_m, o.padding);
    }
  }
  if (W > o.max_size || H > o.max_size)
    refuse(texel_m * std::sqrt(double(W) * double(H)) / double(o.max_size) * 1.05,
           "a " + std::to_string(W) + "x" + std::to_string(H) + " texture");
  tick(0.9);
  out.width = W;
  out.height = H;
  out.texel_m = texel_m;
  std::vector<int> stamp(m.position.size(), -1), local(m.position.size(), -1);
  for (std::size_t ci = 0; ci < charts.size(); ++ci) {
    const ChartBuild& c = charts[ci];
    out.charts.push_back({c.x0, c.y0, c.rect_w, c.rect_h, int(c.faces.size())});
    for (std::size_t i = 0; i < c.verts.size(); ++i) {
      const int v = c.verts[i];
      stamp[std::size_t(v)] = int(ci);
      local[std::size_t(v)] = int(out.mesh.position.size());
      out.mesh.position.push_back(m.position[std::size_t(v)]);
      if (m.normal.size() == m.position.size()) out.mesh.normal.push_back(m.normal[std::size_t(v)]);
      if (m.radiance.size() == m.position.size()) out.mesh.radiance.push_back(m.radiance[std::size_t(v)]);
      out.source.push_back(v);
      const Float2 t = b.LocalTexel(c, i, texel_m);
      out.texel.push_back({t.x + float(c.x0 + o.padding), t.y + float(c.y0 + o.padding)});
    }
    for (int f : c.faces) {
      const auto& t = m.triangles[std::size_t(f)];
      out.chart.push_back(int(ci));
      out.mesh.triangles.push_back({local[std::size_t(t[0])], local[std::size_t(t[1])], local[std::size_t(t[2])]});
    }
  }
  tick(1.0);
  return out;
}

}  // namespace hdrf::mesh
