// UV atlas and texture bake: constructed meshes with known answers (charts, density,
// overlaps, a known pattern seen past an occluder), and the built-in room scanned, baked
// from its keyframes and measured against the scene's true radiance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "common/error.h"
#include "mesh/cleanup.h"
#include "mesh/texture_bake.h"
#include "mesh/uv_atlas.h"
#include "pipeline/keyframes.h"
#include "pipeline/scan_session.h"
#include "sim/synthetic_source.h"
#include "support/sim_frames.h"

namespace hdrf::mesh {
namespace {

// A w x h rectangle at depth z (normal -z, towards cameras at the origin), n x n quads.
void AddRect(Mesh& m, float x0, float y0, float x1, float y1, float z, int n, Float3 radiance) {
  const auto base = std::int32_t(m.position.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.position.push_back({x0 + (x1 - x0) * float(i) / float(n), y0 + (y1 - y0) * float(j) / float(n), z});
      m.normal.push_back({0, 0, -1});
      m.radiance.push_back(radiance);
    }
  auto id = [&](int i, int j) { return base + std::int32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
      m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
    }
}

// An axis-aligned cube of side s centred at the origin, each face n x n quads, normals out.
Mesh Cube(float s, int n) {
  Mesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      const auto base = std::int32_t(m.position.size());
      Float3 nrm{0, 0, 0};
      (axis == 0 ? nrm.x : axis == 1 ? nrm.y : nrm.z) = float(sign);
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          const float u = s * (float(i) / float(n) - 0.5f), v = s * (float(j) / float(n) - 0.5f), w = 0.5f * s * float(sign);
          m.position.push_back(axis == 0 ? Float3{w, u, v} : axis == 1 ? Float3{v, w, u} : Float3{u, v, w});
          m.normal.push_back(nrm);
          m.radiance.push_back({1, 1, 1});
        }
      auto id = [&](int i, int j) { return base + std::int32_t(j * (n + 1) + i); };
      const auto add = [&](std::int32_t a, std::int32_t b, std::int32_t c) {
        const Float3 cr = Cross(m.position[std::size_t(b)] - m.position[std::size_t(a)],
                                m.position[std::size_t(c)] - m.position[std::size_t(a)]);
        if (Dot(cr, nrm) < 0) std::swap(b, c);  // one winding for the whole cube
        m.triangles.push_back({a, b, c});
      };
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          add(id(i, j), id(i + 1, j), id(i + 1, j + 1));
          add(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    }
  return m;
}

double AtlasArea(const Atlas& a, std::size_t t) {
  const auto& tri = a.mesh.triangles[t];
  const Float2 p = a.texel[std::size_t(tri[0])], q = a.texel[std::size_t(tri[1])], r = a.texel[std::size_t(tri[2])];
  return 0.5 * std::abs(double(q.x - p.x) * (r.y - p.y) - double(q.y - p.y) * (r.x - p.x));
}

TEST(UvAtlas, CubeGetsSixChartsAtTheDensityWithoutOverlap) {
  const Mesh cube = Cube(0.5f, 8);
  AtlasOptions o;
  o.texel_m = 0.005;
  const Atlas a = BuildAtlas(cube, o);
  EXPECT_EQ(a.charts.size(), 6u);
  EXPECT_EQ(a.mesh.triangles.size(), cube.triangles.size());
  EXPECT_EQ(a.overlap_splits, 0);
  EXPECT_EQ(CountOverlappingTexels(a), 0);
  // Each face's 9x9 vertices once per chart: seams split, nothing else.
  EXPECT_EQ(a.mesh.position.size(), 6u * 81u);
  for (std::size_t v = 0; v < a.mesh.position.size(); ++v) {
    const Float3 d = a.mesh.position[v] - cube.position[std::size_t(a.source[v])];
    ASSERT_EQ(Length(d), 0.f);
    ASSERT_GE(a.texel[v].x, float(a.padding) - 1e-3f);
    ASSERT_GE(a.texel[v].y, float(a.padding) - 1e-3f);
    ASSERT_LE(a.texel[v].x, float(a.width - 1 - a.padding) + 1e-3f);
    ASSERT_LE(a.texel[v].y, float(a.height - 1 - a.padding) + 1e-3f);
  }
  // Density: texel area / surface area = 1 / texel^2 for every triangle (planar faces).
  for (std::size_t t = 0; t < a.mesh.triangles.size(); ++t)
    ASSERT_NEAR(AtlasArea(a, t) / TriangleArea(a.mesh, t), 1 / (o.texel_m * o.texel_m), 1e-3 / (o.texel_m * o.texel_m));
  // Chart rectangles keep apart (padding on both sides).
  for (std::size_t i = 0; i < a.charts.size(); ++i)
    for (std::size_t j = i + 1; j < a.charts.size(); ++j) {
      const Chart &p = a.charts[i], &q = a.charts[j];
      const bool apart = p.x0 + p.width <= q.x0 || q.x0 + q.width <= p.x0 || p.y0 + p.height <= q.y0 || q.y0 + q.height <= p.y0;
      ASSERT_TRUE(apart) << i << " " << j;
    }
  std::printf("cube: %zu charts, atlas %dx%d, utilisation %.2f\n", a.charts.size(), a.width, a.height, a.Utilisation());
  EXPECT_GT(a.Utilisation(), 0.5);
}

TEST(UvAtlas, FitsATextureSizeAndRefusesADensityTooFine) {
  const Mesh cube = Cube(1.0f, 6);
  AtlasOptions o;
  o.fit_size = 512;
  const Atlas a = BuildAtlas(cube, o);
  EXPECT_LE(std::max(a.width, a.height), 512);
  EXPECT_GE(std::max(a.width, a.height), 460);
  AtlasOptions fine;
  fine.texel_m = 0.0001;  // 0.1 mm on 6 m^2: far beyond 8192^2
  try {
    BuildAtlas(cube, fine);
    FAIL() << "a density needing more than the largest texture was accepted";
  } catch (const SettingError& e) {
    EXPECT_NE(std::string(e.what()).find("mm"), std::string::npos) << e.what();
  }
  AtlasOptions bad;
  bad.padding = -1;
  EXPECT_THROW(BuildAtlas(cube, bad), SettingError);
}

TEST(UvAtlas, CurvedSurfaceIsSplitIntoChartsThatNeverOverlap) {
  // A hemisphere-like cap: normals spread over 90 degrees, so several charts.
  Mesh m;
  const int n = 40;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float th = float(M_PI) * 0.5f * float(j) / float(n), ph = 2 * float(M_PI) * float(i) / float(n);
      const Float3 p{std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
      m.position.push_back(p * 0.3f);
      m.normal.push_back(p);
      m.radiance.push_back({1, 1, 1});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto a = std::int32_t(j * (n + 1) + i), b = a + 1, c = a + n + 2, d = a + n + 1;
      m.triangles.push_back({a, c, b});
      m.triangles.push_back({a, d, c});
    }
  AtlasOptions o;
  o.texel_m = 0.002;
  const Atlas a = BuildAtlas(m, o);
  std::printf("cap: %zu triangles (with degenerate ones at the pole) -> %zu charts, %ld split again, atlas %dx%d\n",
              m.triangles.size(), a.charts.size(), a.overlap_splits, a.width, a.height);
  EXPECT_GE(a.charts.size(), 3u);
  EXPECT_EQ(CountOverlappingTexels(a), 0);
}

// A known radiance pattern on a plane at z = 2, and a bright occluder at z = 1.5 in front of
// part of it, seen by three cameras: the bake recovers the pattern where any camera saw it
// and never takes the occluder's radiance for the plane's.
Float3 Pattern(float x, float y) {
  const bool on = (int(std::floor(x / 0.05f)) + int(std::floor(y / 0.05f))) % 2 == 0;
  return on ? Float3{1.0f, 0.8f, 0.6f} : Float3{0.1f, 0.12f, 0.15f};
}

TEST(TextureBake, RecoversAKnownPatternAndRespectsOcclusion) {
  Mesh m;
  AddRect(m, -0.5f, -0.5f, 0.5f, 0.5f, 2.0f, 20, {0.5f, 0.5f, 0.5f});   // volume radiance: 0.5 grey
  AddRect(m, -0.1f, -0.1f, 0.1f, 0.1f, 1.5f, 4, {50, 50, 50});
  const Float3 occluder{50, 50, 50};
  const PinholeCamera cam{320, 240, 300, 300, 159.5f, 119.5f};
  const std::vector<float> xs = {-0.3f, 0.0f, 0.3f};
  std::vector<BakeView> views;
  for (float cx : xs) {
    BakeView v;
    v.camera = cam;
    v.T_world_camera = Pose::Identity();
    v.T_world_camera.translation() = Eigen::Vector3d(cx, 0, 0);
    v.radiance = RadianceImage(cam.width, cam.height);
    v.confidence = Image<float>(cam.width, cam.height, 1.0f);
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const Float3 d = cam.BackProject(float(x), float(y), 1.0f);
        const float t_occ = 1.5f;
        const float ox = cx + d.x * t_occ, oy = d.y * t_occ;
        if (std::abs(ox) <= 0.1f && std::abs(oy) <= 0.1f) {
          v.radiance(x, y) = occluder;
        } else {
          v.radiance(x, y) = Pattern(cx + d.x * 2.0f, d.y * 2.0f);
        }
      }
    views.push_back(std::move(v));
  }
  AtlasOptions ao;
  ao.texel_m = 0.005;
  const Atlas atlas = BuildAtlas(m, ao);
  const BakedTexture tex = BakeTexture(atlas, views);
  EXPECT_GT(tex.surface_texels, 40000);
  long visible = 0, visible_ok = 0, hidden = 0, hidden_volume = 0, leaks = 0;
  std::vector<double> err;
  for (int y = 0; y < atlas.height; ++y)
    for (int x = 0; x < atlas.width; ++x) {
      const int t = tex.triangle(x, y);
      if (t < 0) continue;
      const auto& tri = atlas.mesh.triangles[std::size_t(t)];
      // The texel's point: interpolate the atlas triangle.
      const Float2 a = atlas.texel[std::size_t(tri[0])], b = atlas.texel[std::size_t(tri[1])], c = atlas.texel[std::size_t(tri[2])];
      const double area = double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x);
      const double w1 = (double(x - a.x) * (c.y - a.y) - double(y - a.y) * (c.x - a.x)) / area;
      const double w2 = (double(b.x - a.x) * (y - a.y) - double(b.y - a.y) * (x - a.x)) / area;
      const Float3 p = atlas.mesh.position[std::size_t(tri[0])] * float(1 - w1 - w2) +
                       atlas.mesh.position[std::size_t(tri[1])] * float(w1) + atlas.mesh.position[std::size_t(tri[2])] * float(w2);
      if (p.z < 1.9f) continue;  // the occluder's own texels (the atlas orders triangles by chart)
      const Float3 value = tex.radiance(x, y);
      if (MaxComponent(value) > 5) ++leaks;
      // Visibility from each camera: the segment camera -> p crosses z = 1.5 outside the occluder
      // (by a margin of 2 cm either way, to stay clear of silhouettes).
      int seen = 0, unseen = 0;
      for (float cx : xs) {
        const float s = 0.5f / 2.0f;  // fraction of the way to the plane at z = 1.5 from p
        const float qx = p.x + (cx - p.x) * s, qy = p.y * (1 - s);
        const float inside = std::max(std::abs(qx), std::abs(qy));
        if (inside > 0.12f) ++seen;
        if (inside < 0.08f) ++unseen;
      }
      if (seen >= 1 && std::abs(p.x) < 0.45f && std::abs(p.y) < 0.45f) {
        ++visible;
        visible_ok += tex.source(x, y) == std::uint8_t(TexelSource::kFrames);
        // The error away from the checker's edges (the views sample the pattern at pixel
        // centres 7 mm apart, so within a pixel of an edge both sides mix).
        const auto edge = [](float u) {
          const float f = u / 0.05f - std::floor(u / 0.05f);
          return 0.05f * std::min(f, 1 - f);
        };
        const Float3 truth = Pattern(p.x, p.y);
        if (edge(p.x) > 0.01f && edge(p.y) > 0.01f) err.push_back(std::abs(std::log2(Luminance(value) / Luminance(truth))));
      } else if (unseen == int(xs.size())) {
        ++hidden;
        hidden_volume += tex.source(x, y) == std::uint8_t(TexelSource::kVolume) && std::abs(value.x - 0.5f) < 1e-4f;
      }
    }
  std::sort(err.begin(), err.end());
  const double median = err[err.size() / 2], p90 = err[err.size() * 9 / 10];
  std::printf("pattern: %ld visible texels (%ld from frames), %ld hidden from all (%ld from the volume), %ld leaks; "
              "error median %.4f stop, 90th percentile %.4f stop; %.2f views per texel\n",
              visible, visible_ok, hidden, hidden_volume, leaks, median, p90, tex.mean_views);
  EXPECT_EQ(leaks, 0);
  EXPECT_GE(double(visible_ok), 0.99 * double(visible));
  EXPECT_GT(hidden, 100);
  EXPECT_GE(double(hidden_volume), 0.99 * double(hidden));
  EXPECT_LT(median, 0.01);
  EXPECT_LT(p90, 0.01);
}

// Gradient magnitudes of log luminance between neighbouring texels (both surface texels of
// one chart, both seen by the frames): their mean over all pairs (the detail measure), the
// mean of the largest 0.25 % (the strength of edges, whatever their position: independent of how well
// the model lines up with the truth), and their mean where the truth is flat (noise).
struct Detail {
  std::vector<double> g;
  double flat = 0, recovered = 0, truth_sum = 0;
  long n_flat = 0;
  void Add(double v, double truth) {
    g.push_back(v);
    if (truth < 0.002) flat += v, ++n_flat;
    recovered += std::min(v, truth), truth_sum += truth;
  }
  // The truth's detail recovered: each pair's gradient counted up to the truth's there, so
  // that noise (a gradient where the truth has none or a smaller one) does not count.
  double Recovered() const { return recovered / std::max(1e-12, truth_sum); }
  double Mean() const {
    double s = 0;
    for (double v : g) s += v;
    return s / double(std::max<std::size_t>(1, g.size()));
  }
  // The mean of the largest 0.25 % (the truth has edges at about 0.5 % of the pairs).
  double Top() const {
    std::vector<double> c = g;
    std::sort(c.begin(), c.end(), std::greater<>());
    const std::size_t n = std::max<std::size_t>(1, c.size() / 400);
    double s = 0;
    for (std::size_t i = 0; i < n; ++i) s += c[i];
    return s / double(n);
  }
  double Flat() const { return flat / double(std::max(1L, n_flat)); }
};

// The built-in room, 300 frames at the default volume: the baked texture against the true
// scene radiance, and its detail against the per-vertex colour's, both against the truth's.
TEST(TextureBake, RoomTextureIsTrueAndSharperThanVertexColour) {
  const auto frames = test::Frames(300, sim::AeMode::kSmooth);
  pipeline::PipelineOptions po;
  const sim::SyntheticSource src{sim::SimOptions()};
  pipeline::ScanSession session(po, sim::SimCamera(320, 240), src.sensor());
  for (const auto& f : frames) session.Process(test::AsInput(f));
  ASSERT_EQ(session.lost(), 0);
  const CleanMesh c = Clean(session.pipeline().ExtractMesh(), {});
  const Atlas atlas = BuildAtlas(c.mesh, {});
  const std::vector<BakeView> views = pipeline::MakeBakeViews(session.keyframes(), session.sensor(), po.pcf);
  const BakedTexture tex = BakeTexture(atlas, views);
  const RadianceImage vertex = VertexRadianceTexture(atlas, tex);
  std::printf("room: %zu keyframes, atlas %dx%d (%zu charts, %.2f used), %ld surface texels, %.1f %% from frames, "
              "%.2f frames per texel\n",
              session.keyframes().size(), atlas.width, atlas.height, atlas.charts.size(), atlas.Utilisation(),
              tex.surface_texels, 100.0 * double(tex.from_frames) / double(tex.surface_texels), tex.mean_views);
  EXPECT_EQ(CountOverlappingTexels(atlas), 0);
  EXPECT_GT(double(tex.from_frames), 0.8 * double(tex.surface_texels));
  // Truth at texel pairs (a random sample: the scene's shading is costly).
  const Pose T0 = frames.front().T_world_camera;  // scene <- model
  const RigidTransform T = ToRigidTransform(T0);
  const sim::Scene& scene = src.scene();
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> ux(0, atlas.width - 2), uy(0, atlas.height - 2);
  const auto point = [&](int x, int y) {
    const auto& tri = atlas.mesh.triangles[std::size_t(tex.triangle(x, y))];
    const Float2 a = atlas.texel[std::size_t(tri[0])], b = atlas.texel[std::size_t(tri[1])], cc = atlas.texel[std::size_t(tri[2])];
    const double area = double(b.x - a.x) * (cc.y - a.y) - double(b.y - a.y) * (cc.x - a.x);
    const double w1 = (double(x - a.x) * (cc.y - a.y) - double(y - a.y) * (cc.x - a.x)) / area;
    const double w2 = (double(b.x - a.x) * (y - a.y) - double(b.y - a.y) * (x - a.x)) / area;
    return atlas.mesh.position[std::size_t(tri[0])] * float(1 - w1 - w2) + atlas.mesh.position[std::size_t(tri[1])] * float(w1) +
           atlas.mesh.position[std::size_t(tri[2])] * float(w2);
  };
  struct Pair {
    Float3 baked[2], vertex[2], truth[2];
  };
  std::vector<Pair> pairs;
  const auto usable = [&](int x, int y) {
    return tex.triangle(x, y) >= 0 && tex.source(x, y) == std::uint8_t(TexelSource::kFrames);
  };
  while (pairs.size() < 40000) {
    const int x = ux(rng), y = uy(rng);
    const bool horizontal = rng() & 1;
    const int x2 = horizontal ? x + 1 : x, y2 = horizontal ? y : y + 1;
    if (!usable(x, y) || !usable(x2, y2)) continue;
    if (atlas.chart[std::size_t(tex.triangle(x, y))] != atlas.chart[std::size_t(tex.triangle(x2, y2))]) continue;
    Pair p;
    p.baked[0] = tex.radiance(x, y), p.baked[1] = tex.radiance(x2, y2);
    p.vertex[0] = vertex(x, y), p.vertex[1] = vertex(x2, y2);
    p.truth[0] = scene.RadianceAt(T.Apply(point(x, y))), p.truth[1] = scene.RadianceAt(T.Apply(point(x2, y2)));
    pairs.push_back(p);
  }
  // One scale per channel (the model's units are the first frame's), as the model evaluation does.
  const auto channel = [](Float3 v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; };
  double scale[3];
  for (int k = 0; k < 3; ++k) {
    std::vector<double> r;
    for (const Pair& p : pairs)
      if (channel(p.baked[0], k) > 0 && channel(p.truth[0], k) > 0) r.push_back(std::log(channel(p.truth[0], k) / channel(p.baked[0], k)));
    scale[k] = std::exp(test::Median(r));
  }
  const auto scaled = [&](Float3 v) { return Float3{float(v.x * scale[0]), float(v.y * scale[1]), float(v.z * scale[2])}; };
  std::vector<double> err_baked, err_vertex;
  Detail baked, vert, truth;
  for (const Pair& p : pairs) {
    for (int k = 0; k < 3; ++k) {
      const double b = channel(scaled(p.baked[0]), k), v = channel(scaled(p.vertex[0]), k), t = channel(p.truth[0], k);
      if (b > 0 && t > 0) err_baked.push_back(std::abs(std::log2(b / t)));
      if (v > 0 && t > 0) err_vertex.push_back(std::abs(std::log2(v / t)));
    }
    const auto grad = [](Float3 a, Float3 b) {
      const double la = Luminance(a), lb = Luminance(b);
      return la > 0 && lb > 0 ? std::abs(std::log(lb / la)) : 0.0;
    };
    const double gt = grad(p.truth[0], p.truth[1]);
    baked.Add(grad(p.baked[0], p.baked[1]), gt);
    vert.Add(grad(p.vertex[0], p.vertex[1]), gt);
    truth.Add(gt, gt);
  }
  const double med_baked = test::Median(err_baked), med_vertex = test::Median(err_vertex);
  std::printf("room texture against the truth (%zu texel pairs): median error %.3f stop (per-vertex colour %.3f)\n"
              "detail, |grad log L| per texel: mean %.4f baked, %.4f per-vertex, %.4f truth (%.2f and %.2f of the "
              "truth's); edges (largest 0.25 %%) %.3f, %.3f, %.3f (%.2f and %.2f); mean where the truth is flat (%ld pairs, "
              "noise) %.4f, %.4f\n",
              pairs.size(), med_baked, med_vertex, baked.Mean(), vert.Mean(), truth.Mean(), baked.Mean() / truth.Mean(),
              vert.Mean() / truth.Mean(), baked.Top(), vert.Top(), truth.Top(), baked.Top() / truth.Top(),
              vert.Top() / truth.Top(), truth.n_flat, baked.Flat(), vert.Flat());
  std::printf("detail recovered (each pair's |grad log L| up to the truth's, over the truth's): %.3f baked, %.3f "
              "per-vertex (%.2fx)\n",
              baked.Recovered(), vert.Recovered(), baked.Recovered() / std::max(1e-12, vert.Recovered()));
  EXPECT_LE(med_baked, 0.1);
  // The detail measure (the mean gradient) at 1.5x the per-vertex colour's. Part of that
  // mean is the frames' noise where the truth is flat, so sharpness is also measured where
  // noise cannot reach it: the edges (largest gradients, wherever they lie) 1.5x as strong as
  // the per-vertex colour's, the detail recovered (noise not counted) above it, and the noise
  // where the truth is flat about 1 % per texel.
  EXPECT_GE(baked.Mean(), 1.5 * vert.Mean());
  EXPECT_GT(baked.Recovered(), 1.1 * vert.Recovered());
  EXPECT_GE(baked.Top() / truth.Top(), 1.5 * vert.Top() / truth.Top());
  EXPECT_LE(baked.Flat(), 0.012);
}

}  // namespace
}  // namespace hdrf::mesh
