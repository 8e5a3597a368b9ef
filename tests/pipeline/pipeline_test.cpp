#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "mesh/incremental_mesh.h"
#include "mesh/mesh.h"
#include "pipeline/pipeline.h"
#include "pipeline/relocaliser.h"
#include "pipeline/scan_session.h"
#include "sim/builtin_sensor.h"
#include "volume/volume.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

TEST(PipelineOptions, ImpossibleVolumesAreRefusedByName) {
  volume::VolumeOptions o;
  o.voxel_m = 0;
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.voxel_m", "between 0.001 and 1 metre"});
  o = {};
  o.voxel_m = std::nanf("");
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.voxel_m"});
  o = {};
  o.truncation_voxels = 1e6f;
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.truncation_voxels", "64"});
  o = {};
  o.max_memory_mb = 1e308;
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.max_memory_mb"});
  o = {};
  o.gpu_memory_mb = 2;  // too small for any view's bricks
  test::ExpectErrorContaining([&] { o.Check(); }, {"volume.gpu_memory_mb", "4 MiB"});
  o.gpu_memory_mb = 0;  // no GPU budget
  o.Check();
  EXPECT_EQ(o.gpu_bricks(), 0u);
  o.gpu_memory_mb = 8;
  EXPECT_EQ(o.gpu_bricks(), std::size_t(8.0 * (1 << 20) / (double(o.brick_bytes()) + 48)));
  pipeline::PipelineOptions po;
  po.pcf = 7;
  test::ExpectErrorContaining([&] { po.Check(); }, {"'pcf'"});
  SensorInfo no_response = sim::BuiltinXtionProfile();
  no_response.response.reset();
  test::ExpectErrorContaining([&] { pipeline::Pipeline p({}, sim::SimCamera(32, 24), no_response); },
                              {"response", "--response srgb"});
}

}  // namespace
}  // namespace hdrf

namespace hdrf::pipeline {
namespace {

std::vector<FrameInput> Inputs(int n) {
  std::vector<FrameInput> in;
  for (const sim::SimFrame& f : test::Frames(n, sim::AeMode::kFlicker)) {
    FrameInput i;
    i.color = f.color.Clone();
    i.depth_m = test::Metres(f.depth);
    i.timestamp = f.timestamp;
    i.exposure_ms = f.exposure_ms;
    in.push_back(std::move(i));
  }
  return in;
}

// |TSDF| of the model at each vertex, in voxels, sorted (vertices outside observed voxels left out).
std::vector<double> TsdfAtVertices(const volume::Volume& model, const volume::VolumeOptions& o,
                                   const std::vector<Float3>& vertices) {
  const float vs = o.voxel_m, trunc = o.truncation_m();
  std::vector<double> off;
  for (const Float3& p : vertices) {
    float f = 0;
    if (model.SampleTsdf(p, &f)) off.push_back(std::fabs(double(f) * trunc / vs));
  }
  std::sort(off.begin(), off.end());
  return off;
}

// The scan session owns what a scan accumulates: its totals are the sums of its reports,
// its trajectory their poses, and the reference is the ray cast from the last pose (frame to
// model) or the last tracked frame (the brightness-constancy tracker, always frame to frame).
TEST(ScanSession, OwnsTheTrajectoryReportsAndTimings) {
  const auto frames = Inputs(6);
  PipelineOptions o;
  o.volume.voxel_m = 0.047f;
  ScanSession s(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  for (const auto& f : frames) s.Process(f);
  ASSERT_EQ(s.frames(), 6);
  ASSERT_EQ(s.poses().size(), 6u);
  StageTimes sum;
  for (const auto& r : s.reports()) sum += r.ms;
  EXPECT_DOUBLE_EQ(s.total_ms().total(), sum.total());
  EXPECT_NEAR(s.mean_ms().track, sum.track / 6, 1e-12);
  EXPECT_GT(s.frames_per_second(), 0);
  EXPECT_EQ(s.timestamps()[5], frames[5].timestamp);
  ASSERT_TRUE(s.exposure_median_relative_error().has_value());
  EXPECT_LT(*s.exposure_median_relative_error(), 0.05);
  Pipeline& p = s.pipeline();
  EXPECT_TRUE(p.backend().HasReference());
  EXPECT_TRUE(p.backend().ReferencePose().isApprox(p.pose()));
  const FrameViews v = p.DownloadViews();
  EXPECT_EQ(v.radiance.width(), 320);
  EXPECT_EQ(v.render.depth.height(), 240);
  const VolumeStats st = p.volume_stats();
  EXPECT_EQ(st.allocated_bricks, s.reports().back().allocated_bricks);
  EXPECT_GT(st.bytes, 0u);

  o.tracker.kind = tracking::TrackerKind::kIntensity;
  ScanSession base(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  for (int i = 0; i < 3; ++i) base.Process(frames[std::size_t(i)]);
  EXPECT_TRUE(base.pipeline().backend().ReferencePose().isApprox(base.poses().back()));
}

// The CPU engine gives the same trajectory on every run (its reductions add the threads'
// partial sums in a fixed order).
TEST(ScanSession, RunsAreReproducible) {
  const auto frames = Inputs(8);
  PipelineOptions o;
  o.volume.voxel_m = 0.047f;
  ScanSession a(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  ScanSession b(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  for (const auto& f : frames) a.Process(f), b.Process(f);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(a.poses()[std::size_t(i)].matrix(), b.poses()[std::size_t(i)].matrix()) << "frame " << i;
    EXPECT_EQ(a.reports()[std::size_t(i)].exposure_ratio, b.reports()[std::size_t(i)].exposure_ratio);
  }
}

// Without stage timing the scan is the same (only its stage times are left out, zero).
TEST(ScanSession, StagesNotTimedGiveTheSameScan) {
  const auto frames = Inputs(8);
  PipelineOptions o;
  o.volume.voxel_m = 0.047f;
  ScanSession a(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  ScanSession b(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  b.pipeline().set_stage_timing(false);
  for (const auto& f : frames) a.Process(f), b.Process(f);
  EXPECT_GT(a.total_ms().total(), 0);
  EXPECT_EQ(b.total_ms().total(), 0);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(a.poses()[std::size_t(i)].matrix(), b.poses()[std::size_t(i)].matrix()) << "frame " << i;
    EXPECT_EQ(a.reports()[std::size_t(i)].exposure_ratio, b.reports()[std::size_t(i)].exposure_ratio);
    EXPECT_EQ(a.reports()[std::size_t(i)].allocated_bricks, b.reports()[std::size_t(i)].allocated_bricks);
  }
}

// A resume point whose ray cast guide does not fit the camera is refused, saying so.
TEST(Pipeline, AResumeGuideOfAnotherSizeIsRefused) {
  PipelineOptions o;
  Pipeline p(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  ResumePoint r;
  r.frames = 1;
  r.anchored = true;
  r.raycast_guide = Image<float>(20, 15, 1.f);
  const volume::Volume model(o.volume);
  test::ExpectErrorContaining([&] { p.Resume(model, r); }, {"ray cast guide", "20x15", "40x30"});
}

// The relocalisation code of a frame: each cell's mean depth of the pixels in it, and the
// same bits whatever the number of threads that build it (its rows are split among them).
TEST(Relocaliser, CodeIsEachCellsMeanAndTheSameBitsForAnyThreadCount) {
  const auto frames = Inputs(2);
  const FrameInput& f = frames[1];
  const radiometry::InverseResponse inv = *sim::BuiltinXtionProfile().response;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const RelocCode one = MakeRelocCode(f.color, f.depth_m, inv);
  ASSERT_FALSE(one.empty());
  ASSERT_EQ(one.width, 40);
  // A cell's depth recomputed here: the mean over the pixels whose cell it is.
  const int W = f.color.width(), H = f.color.height();
  int checked = 0;
  for (int cy : {3, one.height / 2, one.height - 2})
    for (int cx : {2, one.width / 2, one.width - 3}) {
      double sum = 0;
      int n = 0, all = 0;
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
          if (y * one.height / H != cy || x * one.width / W != cx) continue;
          ++all;
          const float z = f.depth_m(x, y);
          if (z > 0) sum += z, ++n;
        }
      const float d = one.depth[std::size_t(cy * one.width + cx)];
      if (2 * n >= all && n > 0) {
        EXPECT_FLOAT_EQ(d, float(sum / n)) << cx << ", " << cy;
        ++checked;
      } else {
        EXPECT_EQ(d, 0.f);
      }
    }
  EXPECT_GE(checked, 5);
  for (int t : {2, 3, 7}) {
    omp_set_num_threads(t);
    const RelocCode c = MakeRelocCode(f.color, f.depth_m, inv);
    EXPECT_TRUE(c.depth == one.depth) << t << " threads";
    EXPECT_TRUE(c.shade == one.shade) << t << " threads";
    EXPECT_TRUE(c.lit == one.lit) << t << " threads";
  }
  omp_set_num_threads(threads);
}

// The studio's surface, kept up to date from the bricks each stretch of frames changed, holds
// exactly the triangles of a whole extraction of the same model; each update meshes only the
// bricks a change reaches; a stretch without frames sends nothing.
TEST(IncrementalMesh, BricksChangedAlongTheScanGiveTheWholeExtractionsTriangles) {
  const auto frames = Inputs(40);
  PipelineOptions o;
  ScanSession s(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  mesh::IncrementalMesher mesher(o.volume);
  std::size_t meshed = 0, sent = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    s.Process(frames[i]);
    if (i % 8 == 7 || i + 1 == frames.size()) {
      const volume::BrickSet changed = s.pipeline().ChangedBricks();
      if (i == 7) {
        EXPECT_EQ(changed.size(), s.pipeline().volume_stats().allocated_bricks);  // the first: every brick
      } else {
        EXPECT_GT(changed.size(), 0u);
        EXPECT_LT(changed.size(), s.pipeline().volume_stats().allocated_bricks);  // later: those seen since
      }
      sent += changed.size();
      meshed += mesher.Apply(changed);
    }
  }
  EXPECT_EQ(s.pipeline().ChangedBricks().size(), 0u);
  EXPECT_EQ(mesher.bricks(), s.pipeline().volume_stats().allocated_bricks);
  const mesh::Mesh whole = s.pipeline().ExtractMesh();
  const mesh::Mesh pieces = mesher.Assemble();
  ASSERT_GT(whole.triangles.size(), 10000u);
  ASSERT_EQ(pieces.triangles.size(), whole.triangles.size());
  EXPECT_GE(pieces.position.size(), whole.position.size());
  EXPECT_LT(pieces.position.size(), whole.position.size() * 13 / 10);  // border vertices repeated
  // Each triangle as its corners' coordinates, starting at the smallest corner (orientation
  // kept): the two lists, sorted, are equal bit for bit.
  const auto corners = [](const mesh::Mesh& m) {
    std::vector<std::array<float, 9>> out;
    for (const auto& t : m.triangles) {
      std::array<Float3, 3> c = {m.position[std::size_t(t[0])], m.position[std::size_t(t[1])], m.position[std::size_t(t[2])]};
      const auto less = [](const Float3& a, const Float3& b) {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
      };
      int first = 0;
      for (int k = 1; k < 3; ++k)
        if (less(c[std::size_t(k)], c[std::size_t(first)])) first = k;
      std::array<float, 9> r;
      for (int k = 0; k < 3; ++k) {
        const Float3& p = c[std::size_t((first + k) % 3)];
        r[std::size_t(3 * k)] = p.x, r[std::size_t(3 * k + 1)] = p.y, r[std::size_t(3 * k + 2)] = p.z;
      }
      out.push_back(r);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_TRUE(corners(pieces) == corners(whole));
  // Normals and radiance of the repeated vertices are those of the whole extraction. (Where a
  // voxel's TSDF is exactly 0, edges of both its cells may place a vertex on it: the whole
  // extraction can hold a position twice, each with its edge's values.)
  std::map<std::array<float, 3>, std::vector<std::size_t>> at;
  for (std::size_t i = 0; i < whole.position.size(); ++i)
    at[{whole.position[i].x, whole.position[i].y, whole.position[i].z}].push_back(i);
  std::size_t same = 0;
  for (std::size_t i = 0; i < pieces.position.size(); ++i) {
    const auto it = at.find({pieces.position[i].x, pieces.position[i].y, pieces.position[i].z});
    ASSERT_TRUE(it != at.end());
    bool found = false;
    for (const std::size_t j : it->second)
      found = found || (pieces.normal[i].x == whole.normal[j].x && pieces.normal[i].y == whole.normal[j].y &&
                        pieces.normal[i].z == whole.normal[j].z && pieces.radiance[i].x == whole.radiance[j].x);
    same += found;
  }
  EXPECT_EQ(same, pieces.position.size());
  // Updates after the first meshed fewer bricks than the model holds each time.
  EXPECT_LT(meshed, 5 * mesher.bricks());
  std::printf("incremental mesh: %zu bricks sent over 5 updates, %zu meshed, model %zu bricks, %zu triangles\n", sent,
              meshed, mesher.bricks(), pieces.triangles.size());
}

// The coarse surface a view previews a scan with (step 2: every other voxel) lies on the
// model's surface and covers what the whole surface covers, with about a quarter of its
// triangles; the bricks changed meanwhile are meshed at step 1 when it is asked for, and
// then give exactly the whole extraction's triangles.
TEST(IncrementalMesh, APreviewAtStepTwoLiesOnTheSurfaceAndTheWholeFollows) {
  const auto frames = Inputs(40);
  PipelineOptions o;
  ScanSession s(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  mesh::IncrementalMesher mesher(o.volume);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    s.Process(frames[i]);
    if (i % 8 == 7) mesher.Apply(s.pipeline().ChangedBricks(), 2);
  }
  const mesh::Mesh preview = mesher.Assemble(2);
  EXPECT_EQ(mesher.pieces(1), 0u);  // nothing meshed at step 1 yet
  const mesh::Mesh whole = s.pipeline().ExtractMesh();
  ASSERT_GT(whole.triangles.size(), 10000u);
  const double share = double(preview.triangles.size()) / double(whole.triangles.size());
  EXPECT_GT(share, 0.12);
  EXPECT_LT(share, 0.40);
  // On the surface: the model's TSDF at each preview vertex, in voxels.
  const std::vector<double> off = TsdfAtVertices(s.pipeline().DownloadVolume(), o.volume, preview.position);
  ASSERT_GT(off.size(), preview.position.size() * 9 / 10);
  const float vs = o.volume.voxel_m;
  const double median = off[off.size() / 2], p95 = off[off.size() * 95 / 100];
  EXPECT_LT(median, 0.25);
  EXPECT_LT(p95, 1.0);
  // Covering the whole surface: a preview vertex within two voxels of (nearly) every vertex
  // of the whole extraction.
  const auto cell = [vs](const Float3& p) {
    return std::array<int, 3>{int(std::floor(p.x / vs)), int(std::floor(p.y / vs)), int(std::floor(p.z / vs))};
  };
  std::set<std::array<int, 3>> cells;
  for (const Float3& p : preview.position) cells.insert(cell(p));
  std::size_t checked = 0, near = 0;
  for (std::size_t i = 0; i < whole.position.size(); i += 7) {
    const auto c = cell(whole.position[i]);
    bool found = false;
    for (int dz = -2; dz <= 2 && !found; ++dz)
      for (int dy = -2; dy <= 2 && !found; ++dy)
        for (int dx = -2; dx <= 2 && !found; ++dx) found = cells.count({c[0] + dx, c[1] + dy, c[2] + dz}) > 0;
    ++checked;
    near += found;
  }
  EXPECT_GT(double(near), 0.98 * double(checked));
  std::printf("preview: %zu of %zu triangles (%.2f), |TSDF| at its vertices median %.3f, 95th %.3f voxels, "
              "%.2f %% of the whole's vertices near one\n",
              preview.triangles.size(), whole.triangles.size(), share, median, p95, 100.0 * double(near) / double(checked));
  // Asked for the whole surface: every brick (stale at step 1) meshed, the whole extraction.
  EXPECT_EQ(mesher.Apply(volume::BrickSet{}, 1), mesher.bricks());
  EXPECT_EQ(mesher.Apply(volume::BrickSet{}, 1), 0u);  // and nothing again after that
  const mesh::Mesh pieces = mesher.Assemble(1);
  EXPECT_EQ(pieces.triangles.size(), whole.triangles.size());
  std::multiset<std::array<float, 3>> a, b;
  for (const Float3& p : pieces.position) a.insert({p.x, p.y, p.z});
  for (const Float3& p : whole.position) b.insert({p.x, p.y, p.z});
  std::set<std::array<float, 3>> sa(a.begin(), a.end()), sb(b.begin(), b.end());
  EXPECT_TRUE(sa == sb);
  test::ExpectErrorContaining([&] { mesher.Apply(volume::BrickSet{}, 3); }, {"step 3"});
}

// A preview's bricks already shown wait their turn (refresh_after): fewer bricks meshed while
// the scan runs, new ones at once, and once the changes stop the same surface as meshing every
// brick every time. Every fourth voxel: a sixteenth-size lattice still on the surface.
TEST(IncrementalMesh, PreviewBricksWaitTheirTurnAndCatchUp) {
  const auto frames = Inputs(40);
  PipelineOptions o;
  ScanSession s(o, sim::SimCamera(320, 240), sim::BuiltinXtionProfile());
  mesh::IncrementalMesher each(o.volume), waiting(o.volume), coarse(o.volume);
  std::size_t meshed_each = 0, meshed_waiting = 0;
  double least_pieces_share = 1;  // the waiting preview's bricks with surface against the other's
  for (std::size_t i = 0; i < frames.size(); ++i) {
    s.Process(frames[i]);
    if (i % 2 == 1) {
      const volume::BrickSet changed = s.pipeline().ChangedBricks();
      meshed_each += each.Apply(changed, 2);
      meshed_waiting += waiting.Apply(changed, 2, 4);
      coarse.Apply(changed, 4, 4);
      least_pieces_share = std::min(least_pieces_share, double(waiting.pieces(2)) / double(std::max<std::size_t>(1, each.pieces(2))));
    }
  }
  // New bricks are not held back: the waiting preview always shows (nearly) every brick with
  // surface that meshing every brick shows.
  ASSERT_GT(each.pieces(2), 100u);
  EXPECT_GT(least_pieces_share, 0.999);
  // The refinement of bricks already shown costs a fraction.
  EXPECT_LT(double(meshed_waiting), 0.7 * double(meshed_each));
  EXPECT_GT(waiting.stale(2), 0u);
  // The changes stopped: the waiting bricks follow within refresh_after calls, then the same
  // surface as meshing every brick every time.
  for (int k = 0; k < 4; ++k) waiting.Apply(volume::BrickSet{}, 2, 4);
  EXPECT_EQ(waiting.stale(2), 0u);
  const mesh::Mesh a = each.Assemble(2), b = waiting.Assemble(2);
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_TRUE(std::equal(a.position.begin(), a.position.end(), b.position.begin(),
                         [](const Float3& p, const Float3& q) { return p.x == q.x && p.y == q.y && p.z == q.z; }));
  // Every fourth voxel: far fewer triangles than every other, still on the surface.
  for (int k = 0; k < 4; ++k) coarse.Apply(volume::BrickSet{}, 4, 4);
  const mesh::Mesh c = coarse.Assemble(4);
  const double share = double(c.triangles.size()) / double(a.triangles.size());
  EXPECT_GT(share, 0.08);
  EXPECT_LT(share, 0.3);
  const std::vector<double> off = TsdfAtVertices(s.pipeline().DownloadVolume(), o.volume, c.position);
  ASSERT_GT(off.size(), c.position.size() * 9 / 10);
  const double median = off[off.size() / 2];
  EXPECT_LT(median, 0.5);
  std::printf("bricks meshed: %zu each time, %zu waiting their turn (least share of pieces %.3f); step 4: %.2f of "
              "step 2's triangles, |TSDF| median %.3f voxels\n",
              meshed_each, meshed_waiting, least_pieces_share, share, median);
}

}  // namespace
}  // namespace hdrf::pipeline
