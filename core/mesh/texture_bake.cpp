#include "mesh/texture_bake.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "common/error.h"
#include "mesh/raster.h"

namespace hdrf::mesh {

void BakeOptions::Check() const {
  if (!(min_cos > 0 && min_cos < 1)) throw SettingError("min_cos", "must be in (0, 1), got " + std::to_string(min_cos));
  if (!(occlusion_tolerance > 0 && occlusion_tolerance < 0.5f))
    throw SettingError("occlusion tolerance", "must be in (0, 0.5) m, got " + std::to_string(occlusion_tolerance));
  if (!(sample_sigma_px >= 0 && sample_sigma_px <= 2))
    throw SettingError("--sample-sigma", "must be 0 (bilinear) to 2 pixels, got " + std::to_string(sample_sigma_px));
  if (edge_margin_px < 0 || edge_margin_px > 16)
    throw SettingError("edge margin", "must be 0 to 16 pixels, got " + std::to_string(edge_margin_px));
}

Float3 SampleBilinear(const RadianceImage& img, float x, float y) {
  const float fx = std::clamp(x, 0.0f, float(img.width() - 1)), fy = std::clamp(y, 0.0f, float(img.height() - 1));
  const int x0 = std::min(int(fx), img.width() - 2 < 0 ? 0 : img.width() - 2);
  const int y0 = std::min(int(fy), img.height() - 2 < 0 ? 0 : img.height() - 2);
  const int x1 = std::min(x0 + 1, img.width() - 1), y1 = std::min(y0 + 1, img.height() - 1);
  const float ax = fx - float(x0), ay = fy - float(y0);
  return (img(x0, y0) * (1 - ax) + img(x1, y0) * ax) * (1 - ay) + (img(x0, y1) * (1 - ax) + img(x1, y1) * ax) * ay;
}

namespace {

struct CameraVertex {
  Float3 p;   // camera frame
  Float2 px;  // pixel
};

// Z-buffered rasterisation of a mesh into a camera: per pixel the nearest triangle and its
// perspective-correct barycentric weights. Triangles reaching closer than 5 cm are skipped.
struct FragmentBuffer {
  DepthImage depth;
  Image<std::int32_t> triangle;
  Image<Float3> weights;
};

FragmentBuffer Rasterize(const Mesh& m, const Pose& T_world_camera, const PinholeCamera& cam, bool need_weights) {
  const RigidTransform T = ToRigidTransform(T_world_camera.inverse());
  std::vector<CameraVertex> v(m.position.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    v[i].p = T.Apply(m.position[i]);
    v[i].px = v[i].p.z > 0.05f ? cam.Project(v[i].p) : Float2{0, 0};
  }
  FragmentBuffer fb{DepthImage(cam.width, cam.height, 0.0f), Image<std::int32_t>(cam.width, cam.height, -1),
                    need_weights ? Image<Float3>(cam.width, cam.height) : Image<Float3>()};
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const CameraVertex& a = v[std::size_t(m.triangles[t][0])];
    const CameraVertex& b = v[std::size_t(m.triangles[t][1])];
    const CameraVertex& c = v[std::size_t(m.triangles[t][2])];
    if (a.p.z <= 0.05f || b.p.z <= 0.05f || c.p.z <= 0.05f) continue;
    const float ia = 1 / a.p.z, ib = 1 / b.p.z, ic = 1 / c.p.z;
    RasterizeTriangle(a.px, b.px, c.px, cam.width, cam.height, [&](int x, int y, float w0, float w1, float w2) {
      const float inv_z = w0 * ia + w1 * ib + w2 * ic;
      const float z = 1 / inv_z;
      float& d = fb.depth(x, y);
      if (d != 0 && d <= z) return;
      d = z;
      fb.triangle(x, y) = std::int32_t(t);
      if (need_weights) fb.weights(x, y) = {w0 * ia * z, w1 * ib * z, w2 * ic * z};
    });
  }
  return fb;
}

// Barycentric weights of a texel centre in an atlas triangle.
Float3 TexelWeights(Float2 a, Float2 b, Float2 c, float x, float y) {
  const double area = double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x);
  if (area == 0) return {1.0f / 3, 1.0f / 3, 1.0f / 3};
  const double w1 = (double(x - a.x) * (c.y - a.y) - double(y - a.y) * (c.x - a.x)) / area;
  const double w2 = (double(b.x - a.x) * (y - a.y) - double(b.y - a.y) * (x - a.x)) / area;
  return {float(1 - w1 - w2), float(w1), float(w2)};
}

struct ViewData {
  const BakeView* view;
  RigidTransform T_camera_world;
  Float3 centre;  // camera centre in the mesh's frame
  DepthImage depth;
};

}  // namespace

DepthImage RenderDepth(const Mesh& m, const Pose& T_world_camera, const PinholeCamera& cam) {
  return std::move(Rasterize(m, T_world_camera, cam, false).depth);
}

namespace {

// The radiance of surface point p (normal n) from the candidate views that see it: the sum of
// the samples' weighted radiance, their weight and the number of views that gave one.
void SampleViews(const std::vector<ViewData>& vd, const BakeOptions& o, Float3 p, Float3 n,
                 const std::vector<int>& cand, Float3& sum, float& wsum, int& count) {
  const bool gaussian = o.sample_sigma_px > 0;
  const float kernel = gaussian ? -0.5f / (o.sample_sigma_px * o.sample_sigma_px) : 0.0f;
  for (int k : cand) {
    const ViewData& d = vd[std::size_t(k)];
    const PinholeCamera& cam = d.view->camera;
    const Float3 pc = d.T_camera_world.Apply(p);
    if (pc.z < 0.1f) continue;
    const Float3 to_cam = d.centre - p;
    const float dist = Length(to_cam);
    const float cosv = Dot(n, to_cam) / dist;
    if (cosv < o.min_cos) continue;
    const Float2 px = cam.Project(pc);
    const int mg = o.edge_margin_px, lim = std::max(mg, 1);
    if (px.x < float(mg) || px.y < float(mg) || px.x > float(cam.width - 1 - lim) || px.y > float(cam.height - 1 - lim))
      continue;
    // The nearest surface there, and no depth edge within the margin.
    const int xi = int(std::lround(px.x)), yi = int(std::lround(px.y));
    const float tol = o.occlusion_tolerance + 0.01f * pc.z;
    bool visible = true;
    for (int dy = -mg; dy <= mg && visible; ++dy)
      for (int dx = -mg; dx <= mg; ++dx) {
        const float z = d.depth(xi + dx, yi + dy);
        if (z == 0 || z < pc.z - tol) {
          visible = false;
          break;
        }
      }
    if (!visible) continue;
    // The four pixels around the point, each weighted by how near its centre is (a
    // Gaussian of the distance in pixels): with several frames sampling the surface at
    // different sub-pixel offsets, each texel leans on the samples taken nearest to it,
    // which keeps edges sharper than averaging every frame's bilinear interpolation.
    const int x0 = int(px.x), y0 = int(px.y);
    const Image<float>& conf = d.view->confidence;
    if (conf(x0, y0) <= 0 || conf(x0 + 1, y0) <= 0 || conf(x0, y0 + 1) <= 0 || conf(x0 + 1, y0 + 1) <= 0) continue;
    const RadianceImage& L = d.view->radiance;
    const float w = cosv * cosv / (pc.z * pc.z);
    for (int yy = y0; yy <= y0 + 1; ++yy)
      for (int xx = x0; xx <= x0 + 1; ++xx) {
        const float dx = px.x - float(xx), dy = px.y - float(yy);
        const float g = (gaussian ? std::exp(kernel * (dx * dx + dy * dy)) : (1 - std::fabs(dx)) * (1 - std::fabs(dy))) *
                        conf(xx, yy) * w;
        sum += L(xx, yy) * g;
        wsum += g;
      }
    ++count;
  }
}

// 1. Surface texels: which triangle owns each texel centre.
void OwnTexels(const Atlas& atlas, BakedTexture& out) {
  const Mesh& m = atlas.mesh;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    RasterizeTriangle(atlas.texel[std::size_t(tri[0])], atlas.texel[std::size_t(tri[1])], atlas.texel[std::size_t(tri[2])],
                      atlas.width, atlas.height, [&](int x, int y, float, float, float) { out.triangle(x, y) = std::int32_t(t); });
  }
}

// 2. Depth buffers of the mesh from every view (occlusion); progress from 0.05 to 0.4.
std::vector<ViewData> ViewDepths(const Mesh& m, const std::vector<BakeView>& views,
                                 const std::function<bool(double)>& progress) {
  std::vector<ViewData> vd(views.size());
  std::atomic<int> done{0};
  std::atomic<bool> cancelled{false};
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < int(views.size()); ++i) {
    if (cancelled) continue;
    ViewData& d = vd[std::size_t(i)];
    d.view = &views[std::size_t(i)];
    d.T_camera_world = ToRigidTransform(views[std::size_t(i)].T_world_camera.inverse());
    const Eigen::Vector3d c = views[std::size_t(i)].T_world_camera.translation();
    d.centre = {float(c.x()), float(c.y()), float(c.z())};
    d.depth = RenderDepth(m, views[std::size_t(i)].T_world_camera, views[std::size_t(i)].camera);
    ++done;
#pragma omp critical
    if (progress && !progress(0.05 + 0.35 * double(done) / double(views.size()))) cancelled = true;
  }
  if (cancelled) throw Cancelled();
  return vd;
}

// 3. Every surface texel from the views that see it (else from the volume's radiance);
// progress from 0.4 to 0.9.
void BakeSurface(const Atlas& atlas, const std::vector<ViewData>& vd, const BakeOptions& o,
                 const std::function<bool(double)>& progress, BakedTexture& out) {
  const Mesh& m = atlas.mesh;
  const int W = atlas.width, H = atlas.height;
  const bool has_normals = m.normal.size() == m.position.size();
  const bool has_radiance = m.radiance.size() == m.position.size();
  std::atomic<bool> cancelled{false};
  std::atomic<long> surface{0}, frames{0}, volume{0}, views_used{0};
  std::atomic<std::size_t> tris_done{0};
  const int nt = int(m.triangles.size());
#pragma omp parallel
  {
    std::vector<int> cand;
    long my_surface = 0, my_frames = 0, my_volume = 0, my_views = 0;
#pragma omp for schedule(dynamic, 256)
    for (int t = 0; t < nt; ++t) {
      if (cancelled) continue;
      const auto& tri = m.triangles[std::size_t(t)];
      const Float3 p0 = m.position[std::size_t(tri[0])], p1 = m.position[std::size_t(tri[1])], p2 = m.position[std::size_t(tri[2])];
      const Float3 centroid = (p0 + p1 + p2) / 3.0f;
      const Float3 cr = Cross(p1 - p0, p2 - p0);
      Float3 fn = Length(cr) > 0 ? Normalized(cr) : Float3{0, 0, 0};
      if (has_normals) {
        const Float3 s = m.normal[std::size_t(tri[0])] + m.normal[std::size_t(tri[1])] + m.normal[std::size_t(tri[2])];
        if (Dot(s, fn) < 0) fn = -fn;
        if (Length(s) > 0) fn = Normalized(s);
      }
      // Views that may see the triangle at all.
      cand.clear();
      for (std::size_t k = 0; k < vd.size(); ++k) {
        const Float3 pc = vd[k].T_camera_world.Apply(centroid);
        if (pc.z < 0.1f) continue;
        const Float3 to_cam = vd[k].centre - centroid;
        if (Dot(fn, to_cam) < (o.min_cos - 0.3f) * Length(to_cam)) continue;
        const Float2 px = vd[k].view->camera.Project(pc);
        const float slack = 0.25f * float(vd[k].view->camera.width);
        if (px.x < -slack || px.y < -slack || px.x > float(vd[k].view->camera.width) + slack ||
            px.y > float(vd[k].view->camera.height) + slack)
          continue;
        cand.push_back(int(k));
      }
      const Float2 ta = atlas.texel[std::size_t(tri[0])], tb = atlas.texel[std::size_t(tri[1])], tc = atlas.texel[std::size_t(tri[2])];
      RasterizeTriangle(ta, tb, tc, W, H, [&](int x, int y, float w0, float w1, float w2) {
        if (out.triangle(x, y) != t) return;  // (a sliver another triangle owns)
        ++my_surface;
        const Float3 p = p0 * w0 + p1 * w1 + p2 * w2;
        Float3 n = fn;
        if (has_normals) {
          const Float3 s = m.normal[std::size_t(tri[0])] * w0 + m.normal[std::size_t(tri[1])] * w1 + m.normal[std::size_t(tri[2])] * w2;
          if (Length(s) > 0) n = Normalized(s);
        }
        Float3 sum{0, 0, 0};
        float wsum = 0;
        int count = 0;
        SampleViews(vd, o, p, n, cand, sum, wsum, count);
        if (wsum > 0) {
          out.radiance(x, y) = sum / wsum;
          out.source(x, y) = std::uint8_t(TexelSource::kFrames);
          ++my_frames;
          my_views += count;
        } else {
          out.radiance(x, y) = has_radiance ? m.radiance[std::size_t(tri[0])] * w0 + m.radiance[std::size_t(tri[1])] * w1 +
                                                  m.radiance[std::size_t(tri[2])] * w2
                                            : Float3{0, 0, 0};
          out.source(x, y) = std::uint8_t(TexelSource::kVolume);
          ++my_volume;
        }
      });
      const std::size_t n_done = ++tris_done;
      if (n_done % 8192 == 0) {
#pragma omp critical
        if (progress && !progress(0.4 + 0.5 * double(n_done) / double(nt))) cancelled = true;
      }
    }
    surface += my_surface;
    frames += my_frames;
    volume += my_volume;
    views_used += my_views;
  }
  out.surface_texels = surface;
  out.from_frames = frames;
  out.from_volume = volume;
  out.mean_views = frames > 0 ? double(views_used) / double(frames) : 0;
  if (cancelled) throw Cancelled();
}

// 4. Charts too small to hold a texel centre: their rectangle takes the radiance at their
// triangles' centroids (frames where seen, else the volume's).
void FillSmallCharts(const Atlas& atlas, const std::vector<ViewData>& vd, const BakeOptions& o, BakedTexture& out) {
  const Mesh& m = atlas.mesh;
  const int W = atlas.width, H = atlas.height;
  const bool has_normals = m.normal.size() == m.position.size();
  const bool has_radiance = m.radiance.size() == m.position.size();
  std::vector<long> per_chart(atlas.charts.size(), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (out.triangle(x, y) >= 0) ++per_chart[std::size_t(atlas.chart[std::size_t(out.triangle(x, y))])];
  std::vector<int> all(vd.size());
  for (std::size_t k = 0; k < vd.size(); ++k) all[k] = int(k);
  std::vector<Float3> small_sum(atlas.charts.size(), Float3{0, 0, 0});
  std::vector<float> small_w(atlas.charts.size(), 0);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const std::size_t c = std::size_t(atlas.chart[t]);
    if (per_chart[c] > 0) continue;
    const auto& tri = m.triangles[t];
    const Float3 p = (m.position[std::size_t(tri[0])] + m.position[std::size_t(tri[1])] + m.position[std::size_t(tri[2])]) / 3.0f;
    Float3 n{0, 0, 1};
    if (has_normals) {
      const Float3 s = m.normal[std::size_t(tri[0])] + m.normal[std::size_t(tri[1])] + m.normal[std::size_t(tri[2])];
      if (Length(s) > 0) n = Normalized(s);
    }
    Float3 sum{0, 0, 0};
    float wsum = 0;
    int count = 0;
    SampleViews(vd, o, p, n, all, sum, wsum, count);
    const float area = 0.5f * Length(Cross(m.position[std::size_t(tri[1])] - m.position[std::size_t(tri[0])],
                                           m.position[std::size_t(tri[2])] - m.position[std::size_t(tri[0])])) + 1e-12f;
    const Float3 value = wsum > 0 ? sum / wsum
                                  : (has_radiance ? (m.radiance[std::size_t(tri[0])] + m.radiance[std::size_t(tri[1])] +
                                                     m.radiance[std::size_t(tri[2])]) / 3.0f
                                                  : Float3{0, 0, 0});
    small_sum[c] += value * area;
    small_w[c] += area;
  }
  for (std::size_t c = 0; c < atlas.charts.size(); ++c) {
    if (per_chart[c] > 0 || small_w[c] <= 0) continue;
    const Chart& ch = atlas.charts[c];
    for (int y = ch.y0; y < std::min(H, ch.y0 + ch.height); ++y)
      for (int x = ch.x0; x < std::min(W, ch.x0 + ch.width); ++x) {
        out.radiance(x, y) = small_sum[c] / small_w[c];
        out.source(x, y) = std::uint8_t(TexelSource::kPadding);
      }
  }
}

// 5. Padding: each chart's empty texels from their filled neighbours in the same chart,
// ring by ring, so filtering and mip levels never mix charts.
void PadCharts(const Atlas& atlas, BakedTexture& out) {
  const int W = atlas.width, H = atlas.height;
  const int rings = atlas.padding + 2;
#pragma omp parallel for schedule(dynamic, 16)
  for (int c = 0; c < int(atlas.charts.size()); ++c) {
    const Chart& ch = atlas.charts[std::size_t(c)];
    const int x1 = std::min(W, ch.x0 + ch.width), y1 = std::min(H, ch.y0 + ch.height);
    std::vector<std::pair<int, int>> next;
    for (int ring = 0; ring < rings; ++ring) {
      next.clear();
      for (int y = ch.y0; y < y1; ++y)
        for (int x = ch.x0; x < x1; ++x) {
          if (out.source(x, y) != 0) continue;
          bool any = false;
          for (int dy = -1; dy <= 1 && !any; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int u = x + dx, v = y + dy;
              if (u < ch.x0 || v < ch.y0 || u >= x1 || v >= y1 || out.source(u, v) == 0) continue;
              any = true;
              break;
            }
          if (any) next.push_back({x, y});
        }
      if (next.empty()) break;
      std::vector<Float3> values(next.size());
      for (std::size_t i = 0; i < next.size(); ++i) {
        const auto [x, y] = next[i];
        Float3 sum{0, 0, 0};
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            if (u < ch.x0 || v < ch.y0 || u >= x1 || v >= y1 || out.source(u, v) == 0) continue;
            sum += out.radiance(u, v);
            ++n;
          }
        values[i] = sum / float(n);
      }
      for (std::size_t i = 0; i < next.size(); ++i) {
        out.radiance(next[i].first, next[i].second) = values[i];
        out.source(next[i].first, next[i].second) = std::uint8_t(TexelSource::kPadding);
      }
    }
  }
}

}  // namespace

BakedTexture BakeTexture(const Atlas& atlas, const std::vector<BakeView>& views, const BakeOptions& o,
                         const std::function<bool(double)>& progress) {
  o.Check();
  const auto tick = [&](double f) {
    if (progress && !progress(f)) throw Cancelled();
  };
  const Mesh& m = atlas.mesh;
  const int W = atlas.width, H = atlas.height;
  BakedTexture out{RadianceImage(W, H), Image<std::uint8_t>(W, H, 0), Image<std::int32_t>(W, H, -1)};
  if (m.triangles.empty()) return out;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const BakeView& v = views[i];
    if (!v.camera.Valid() || v.radiance.width() != v.camera.width || v.radiance.height() != v.camera.height ||
        v.confidence.width() != v.camera.width || v.confidence.height() != v.camera.height)
      throw Error("texture bake: view " + std::to_string(i) + " has images of another size than its camera");
  }
  OwnTexels(atlas, out);
  tick(0.05);
  const std::vector<ViewData> vd = ViewDepths(m, views, progress);
  BakeSurface(atlas, vd, o, progress, out);
  FillSmallCharts(atlas, vd, o, out);
  PadCharts(atlas, out);
  tick(1.0);
  return out;
}

RadianceImage VertexRadianceTexture(const Atlas& atlas, const BakedTexture& layout) {
  const Mesh& m = atlas.mesh;
  RadianceImage out(atlas.width, atlas.height);
  if (m.radiance.size() != m.position.size()) return out;
  for (int y = 0; y < atlas.height; ++y)
    for (int x = 0; x < atlas.width; ++x) {
      const int t = layout.triangle(x, y);
      if (t < 0) continue;
      const auto& tri = m.triangles[std::size_t(t)];
      const Float3 w = TexelWeights(atlas.texel[std::size_t(tri[0])], atlas.texel[std::size_t(tri[1])],
                                    atlas.texel[std::size_t(tri[2])], float(x), float(y));
      out(x, y) = m.radiance[std::size_t(tri[0])] * w.x + m.radiance[std::size_t(tri[1])] * w.y +
                  m.radiance[std::size_t(tri[2])] * w.z;
    }
  return out;
}

TexturedRender RenderTextured(const Atlas& atlas, const RadianceImage& texture, const Pose& T_world_camera,
                              const PinholeCamera& cam) {
  if (!cam.Valid()) throw SettingError("render size", "the camera needs a positive size and focal length");
  FragmentBuffer fb = Rasterize(atlas.mesh, T_world_camera, cam, true);
  TexturedRender r{RadianceImage(cam.width, cam.height), Image<float>(cam.width, cam.height, 0.0f),
                   std::move(fb.depth)};
  const bool textured = texture.width() == atlas.width && texture.height() == atlas.height && atlas.width > 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const int t = fb.triangle(x, y);
      if (t < 0) continue;
      const auto& tri = atlas.mesh.triangles[std::size_t(t)];
      const Float3 w = fb.weights(x, y);
      r.alpha(x, y) = 1;
      if (textured) {
        const Float2 a = atlas.texel[std::size_t(tri[0])], b = atlas.texel[std::size_t(tri[1])], c = atlas.texel[std::size_t(tri[2])];
        r.radiance(x, y) = SampleBilinear(texture, a.x * w.x + b.x * w.y + c.x * w.z, a.y * w.x + b.y * w.y + c.y * w.z);
      } else if (atlas.mesh.radiance.size() == atlas.mesh.position.size()) {
        r.radiance(x, y) = atlas.mesh.radiance[std::size_t(tri[0])] * w.x + atlas.mesh.radiance[std::size_t(tri[1])] * w.y +
                           atlas.mesh.radiance[std::size_t(tri[2])] * w.z;
      }
    }
  return r;
}

}  // namespace hdrf::mesh
