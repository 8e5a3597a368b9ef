#include <gtest/gtest.h>

#include <type_traits>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "imaging/imaging.h"
#include "eval/eval.h"
#include "normalized_radiance/normalized_radiance.h"
#include "pipeline/frame_source.h"
#include "pipeline/pipeline.h"
#include "radiometry/pcf.h"
#include "radiometry/radiance.h"
#include "sim/builtin_sensor.h"
#include "volume/volume.h"
#include "volume/project_brick.h"
#include "volume/raycast_driver.h"
#include "volume/volume_impl.h"
#include "eval/eval.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

// Brick coordinates read back from a file (a project) are range-checked without overflow:
// the fuzzer's project with a brick at x = 2^31 - 1 made `x + range` overflow (UBSan); such
// bricks, and those just outside the range, are refused, the edges of the range accepted.
TEST(Volume, AssignRefusesBricksOutOfRangeForAnyCoordinate) {
  volume::VolumeOptions o;
  volume::Volume v(o);
  const auto assign = [&](std::array<int, 3> c) {
    v.Assign(std::vector<std::uint8_t>(o.brick_bytes()), {c}, "");
  };
  constexpr int r = volume::kBrickRange;
  for (const int bad : {INT_MAX, INT_MIN, r, -r - 1, INT_MAX - r + 1}) {
    EXPECT_THROW(assign({bad, 0, 0}), Error) << bad;
    EXPECT_THROW(assign({0, bad, 0}), Error) << bad;
    EXPECT_THROW(assign({0, 0, bad}), Error) << bad;
  }
  for (const int good : {-r, r - 1, 0}) EXPECT_NO_THROW(assign({good, good, good})) << good;
}

TEST(Volume, FusedDepthMatchesTruthAndRaycastAgrees) {
  const auto frames = Frames(12, sim::AeMode::kFixed, /*exact_depth=*/true);
  volume::VolumeOptions vo;
  volume::Volume vol(vo);
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const Pose T0inv = frames[0].T_world_camera.inverse();
  for (const auto& f : frames) {
    const DepthImage d = Metres(f.depth);
    const auto v = imaging::VertexMap(d, cam);
    const auto n = imaging::NormalMap(v);
    Image<float> one(320, 240, 1.f);
    RadianceImage r = f.radiance.Clone();
    volume::Volume::FrameInput in{&d, &n, &r, &one, &one, &one, cam, T0inv * f.T_world_camera};
    vol.Integrate(in);
  }
  const auto& last = frames.back();
  const auto rend = vol.Raycast(cam, T0inv * last.T_world_camera);
  std::vector<double> err;
  long inside = 0;
  const Pose T = T0inv * last.T_world_camera;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const float z = last.depth_true(x, y);
      if (!(z > 0)) continue;
      const Float3 pc = cam.BackProject(float(x), float(y), z);
      const Vec3 pw = T * Vec3(pc.x, pc.y, pc.z);
      ++inside;
      if (rend.depth(x, y) > 0) err.push_back(std::abs(rend.depth(x, y) - z));
    }
  const double coverage = double(err.size()) / double(inside);
  std::printf("ray cast vs true depth: median |error| %.4f m (voxel %.4f), coverage %.3f, %zu bricks\n",
              Median(err), vo.voxel_m, coverage, vol.allocated_bricks());
  EXPECT_LT(Median(err), 0.25 * vo.voxel_m);
  EXPECT_GT(coverage, 0.9);
}

// Rays started near the surface the fused frame's depth shows (the tracker's ray cast) find
// the surface the rays from near find, to a small fraction of a voxel, on noisy depth; a tile
// with a pixel of no depth starts at near; and a surface in front of what the depth shows
// (the model's, not seen now) is left out only where it lies before the tile's guide.
TEST(Volume, RaysStartedNearTheFusedDepthFindTheSameSurface) {
  const auto frames = Frames(20, sim::AeMode::kFixed);
  volume::VolumeOptions vo;
  volume::Volume vol(vo);
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const Pose T0inv = frames[0].T_world_camera.inverse();
  DepthImage last_depth;
  for (const auto& f : frames) {
    last_depth = Metres(f.depth);
    const auto v = imaging::VertexMap(last_depth, cam);
    const auto n = imaging::NormalMap(v);
    Image<float> one(320, 240, 1.f);
    RadianceImage r = f.radiance.Clone();
    volume::Volume::FrameInput in{&last_depth, &n, &r, &one, &one, &one, cam, T0inv * f.T_world_camera};
    vol.Integrate(in);
  }
  const Pose T = T0inv * frames.back().T_world_camera;
  constexpr int kT = volume::kGuideTile;
  const int tw = volume::GuideTiles(320), th = volume::GuideTiles(240);
  Image<float> guide(tw, th);
  ASSERT_EQ(tw, (320 + kT - 1) / kT);
  ASSERT_EQ(th, (240 + kT - 1) / kT);
  volume::RaycastGuide(par::Host{}, View(last_depth), vo.truncation_m(), View(guide));
  int guided_tiles = 0;
  for (int ty = 0; ty < th; ++ty)
    for (int tx = 0; tx < tw; ++tx) {
      float lo = 1e9f;
      bool all = true;
      for (int y = kT * ty; y < std::min(240, kT * ty + kT); ++y)
        for (int x = kT * tx; x < std::min(320, kT * tx + kT); ++x)
          all = all && last_depth(x, y) > 0, lo = std::min(lo, last_depth(x, y));
      EXPECT_FLOAT_EQ(guide(tx, ty), all ? lo - vo.truncation_m() : 0.f) << tx << " " << ty;
      guided_tiles += guide(tx, ty) > 0;
    }
  EXPECT_GT(guided_tiles, tw * th / 2);
  const auto from_near = vol.Raycast(cam, T);
  const auto guided = vol.Raycast(cam, T, &guide);
  long both = 0, only_near = 0, only_guided = 0, close = 0, within = 0;
  double worst = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const bool a = from_near.depth(x, y) > 0, b = guided.depth(x, y) > 0;
      only_near += a && !b;
      only_guided += b && !a;
      if (!(a && b)) continue;
      ++both;
      const double d = std::abs(double(from_near.depth(x, y)) - double(guided.depth(x, y)));
      worst = std::max(worst, d);
      close += d < 0.05 * vo.voxel_m;
      within += d < 0.25 * vo.voxel_m;
    }
  std::printf("guided ray cast: %d of %d tiles guided; %ld pixels hit by both, %ld only from near, %ld only guided; "
              "%.2f %% within 1 mm, %.2f %% within 5 mm, largest difference %.2f mm\n",
              guided_tiles, tw * th, both, only_near, only_guided, 100.0 * double(close) / double(both),
              100.0 * double(within) / double(both), 1e3 * worst);
  EXPECT_GT(both, 55000);
  EXPECT_LE(only_near + only_guided, both / 500);
  // Other samples along the ray: the zero crossing is interpolated between other TSDF values
  // (noisy depth), so a few pixels differ by more than a twentieth of a voxel.
  EXPECT_GE(double(close), 0.97 * double(both));
  EXPECT_GE(double(within), 0.995 * double(both));
  // A wall of the model 0.5 m in front of what the depth shows, across the guided tiles: the
  // rays from near meet it, the guided ones start behind it.
  Image<float> far_guide = guide.Clone();
  for (std::size_t i = 0; i < far_guide.size(); ++i) far_guide[i] = far_guide[i] > 0 ? far_guide[i] + 0.5f : 0.f;
  const auto skipped = vol.Raycast(cam, T, &far_guide);
  long deeper = 0, in_guided = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x)
      if (far_guide(x / kT, y / kT) > 0 && from_near.depth(x, y) > 0) {
        ++in_guided;
        deeper += !(skipped.depth(x, y) > 0) || skipped.depth(x, y) > from_near.depth(x, y) + 0.2f;
      }
  // The guide decides where rays begin: it must come from the depth fused at that pose.
  EXPECT_GT(in_guided, 30000);
  EXPECT_GE(double(deeper), 0.95 * double(in_guided));
}

// A volume with the frames fused at their true poses (relative to the first).
volume::Volume FuseFrames(const volume::VolumeOptions& vo, const std::vector<sim::SimFrame>& frames, const PinholeCamera& cam) {
  const Pose T0inv = frames[0].T_world_camera.inverse();
  volume::Volume vol(vo);
  for (const auto& f : frames) {
    const DepthImage depth = Metres(f.depth);
    const auto v = imaging::VertexMap(depth, cam);
    const auto n = imaging::NormalMap(v);
    Image<float> one(cam.width, cam.height, 1.f);
    RadianceImage r = f.radiance.Clone();
    vol.Integrate({&depth, &n, &r, &one, &one, &one, cam, T0inv * f.T_world_camera});
  }
  return vol;
}

// Calls f(options, view) for each voxel encoding, with the frames fused (FuseFrames).
template <typename F>
void ForEachEncodingFused(const std::vector<sim::SimFrame>& frames, const PinholeCamera& cam, F&& f) {
  for (const auto enc : {volume::VoxelEncoding::kFull, volume::VoxelEncoding::kNoNr, volume::VoxelEncoding::kCompact}) {
    volume::VolumeOptions vo;
    vo.encoding = enc;
    const volume::Volume vol = FuseFrames(vo, frames, cam);
    volume::VisitEncoding(enc, [&](auto tag) { f(vo, vol.view<decltype(tag)>()); });
  }
}

// The CPU integration's first pass takes a brick's voxels four at a time (ProjectBrick): the
// same voxels, in the same order, with the same camera positions, pixels and distances, bit
// for bit, as ProjectVoxel one by one (what the GPU runs). Poses that put bricks behind the
// camera, across the image's edges and straddling the depth; a depth image with holes.
TEST(Volume, ProjectBrickGivesProjectVoxelsBits) {
  const PinholeCamera cam = sim::SimCamera(160, 120);
  DepthImage depth(cam.width, cam.height);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      depth(x, y) = (x * 7 + y * 3) % 23 == 0 ? 0.f : 0.6f + 0.004f * float((x * 13 + y * 5) % 97);
  volume::IntegrateArgs a{};
  a.depth = View(depth);
  a.cam = cam;
  a.voxel_m = 0.02f;
  a.trunc_m = 0.08f;
  long in_view = 0, partial = 0, bricks = 0;
  for (int p = 0; p < 6; ++p) {
    Pose T = Pose::Identity();
    T.rotate(Eigen::AngleAxisd(0.3 * p - 0.7, Eigen::Vector3d(0.2, 1, 0.1 * p).normalized()));
    T.pretranslate(Eigen::Vector3d(0.05 * p - 0.1, -0.03 * p, 0.02 * p));
    a.T_camera_world = ToRigidTransform(T);
    for (int bz = -2; bz <= 8; ++bz)
      for (int by = -4; by <= 3; ++by)
        for (int bx = -5; bx <= 4; ++bx) {
          volume::VoxelInView one[512], four[512];
          std::int16_t at_one[512], at_four[512];
          int n = 0;
          for (int i = 0; i < 512; ++i)
            if (volume::ProjectVoxel(a, bx, by, bz, i, &one[n])) at_one[n++] = std::int16_t(i);
          const int m = volume::ProjectBrick(a, bx, by, bz, four, at_four);
          ASSERT_EQ(m, n) << "pose " << p << ", brick " << bx << " " << by << " " << bz;
          for (int k = 0; k < n; ++k) {
            ASSERT_EQ(at_four[k], at_one[k]);
            ASSERT_EQ(std::memcmp(&four[k].pc, &one[k].pc, sizeof(Float3)), 0) << "voxel " << at_one[k];
            ASSERT_EQ(four[k].u, one[k].u);
            ASSERT_EQ(four[k].v, one[k].v);
            ASSERT_EQ(std::memcmp(&four[k].sdf, &one[k].sdf, sizeof(float)), 0);
          }
          in_view += n;
          partial += n > 0 && n < 512;
          ++bricks;
        }
  }
  std::printf("[ figures  ] %ld bricks, %ld voxels in view, %ld bricks partly\n", bricks, in_view, partial);
  EXPECT_GT(in_view, 20000);
  EXPECT_GT(partial, 100);
}

// The trilinear samples' short way (a cell inside one brick: one look-up, fixed offsets)
// gives exactly the bits of the general way (each corner's brick found on its own), with and
// without a hint, for every encoding: the ray cast and the tracker's reference do not change.
TEST(Volume, TrilinearShortWayGivesTheGeneralWaysBits) {
  const auto frames = Frames(6, sim::AeMode::kFixed);
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const Pose T0inv = frames[0].T_world_camera.inverse();
  ForEachEncodingFused(frames, cam, [&](const volume::VolumeOptions& vo, const auto& vv) {
      using View = std::decay_t<decltype(vv)>;
      const volume::VoxelEncoding enc = vo.encoding;
      // Points along the last view's rays, around the surface it shows and between.
      const DepthImage depth = Metres(frames.back().depth);
      const Pose T = T0inv * frames.back().T_world_camera;
      std::uint32_t state = 12345u;
      auto uniform = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1u << 24); };
      long tsdf_both = 0, tsdf_short = 0, rad_both = 0, differ = 0, one_brick = 0;
      for (int i = 0; i < 200000; ++i) {
        const int x = int(uniform() * 319.f), y = int(uniform() * 239.f);
        const float z = depth(x, y) > 0 ? depth(x, y) + (uniform() - 0.5f) * 4.f * vo.truncation_m() : 1.f + 3.f * uniform();
        const Eigen::Vector3d pw = T * Eigen::Vector3d(cam.BackProject(float(x), float(y), z).x,
                                                       cam.BackProject(float(x), float(y), z).y, z);
        const Float3 p{float(pw.x()), float(pw.y()), float(pw.z())};
        const Float3 g = vv.Grid(p);
        const int gx = int(std::floor(g.x)), gy = int(std::floor(g.y)), gz = int(std::floor(g.z));
        one_brick += (gx & 7) != 7 && (gy & 7) != 7 && (gz & 7) != 7;
        typename View::BrickHint hint;
        if (i % 2) {  // half with the brick of a point a voxel away as the hint
          hint.bx = (gx + 1) >> 3, hint.by = gy >> 3, hint.bz = gz >> 3, hint.valid = true;
          hint.slot = vv.Slot(hint.bx, hint.by, hint.bz);
        }
        float a = -7.f, b = -7.f;
        const bool sa = vv.SampleTsdf(p, &a, hint), sb = vv.SampleTsdf(p, &b, hint, false);
        tsdf_short += sa;
        if (sa != sb || std::memcmp(&a, &b, sizeof a) != 0) ++differ;
        tsdf_both += sa && sb;
        Float3 ra{-7, -7, -7}, rb{-7, -7, -7};
        float na = -7.f, nb = -7.f;
        const bool qa = vv.SampleRadiance(p, &ra, &na, hint), qb = vv.SampleRadiance(p, &rb, &nb, hint, false);
        if (qa != qb || std::memcmp(&ra, &rb, sizeof ra) != 0 || std::memcmp(&na, &nb, sizeof na) != 0) ++differ;
        rad_both += qa && qb;
      }
      std::printf("%s: %ld of 200000 points in one brick's cell; TSDF defined at %ld, radiance at %ld; %ld differ\n",
                  volume::VoxelEncodingName(enc), one_brick, tsdf_both, rad_both, differ);
      EXPECT_EQ(differ, 0);
      EXPECT_GT(tsdf_both, 40000);  // the comparison covers many defined samples of both kinds
      EXPECT_GT(rad_both, 40000);
      EXPECT_GT(one_brick, 100000);
      EXPECT_LT(one_brick, 180000);
  });
}

// The GPU's ray cast in two passes (RaycastInTwoPasses: each ray's walk, its crossing kept in
// the depth image, then the hits' shading with no brick hint) gives the one pass's images
// byte for byte (RaycastInto on the CPU: walk and shading in turn, the walk's last brick
// reused), for every encoding: from the last frame's pose from near and guided, from 0.8 m
// behind it (each with tens of thousands of hits), and turned about (no hit: every ray leaves
// the model's box or meets only surfaces seen from behind, and both forms must leave zeros).
TEST(Volume, RayCastInTwoPassesGivesTheOnePassImages) {
  const auto frames = Frames(12, sim::AeMode::kFixed);
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const Pose T0inv = frames[0].T_world_camera.inverse();
  const Pose T = T0inv * frames.back().T_world_camera;
  Pose back = T, turned = T;
  back.translation() -= 0.8 * T.linear().col(2);
  turned.linear() = T.linear() * Eigen::AngleAxisd(3.14159265358979, Eigen::Vector3d::UnitY()).toRotationMatrix();
  ForEachEncodingFused(frames, cam, [&](const volume::VolumeOptions& vo, const auto& vv) {
    const DepthImage depth = Metres(frames.back().depth);
    Image<float> guide(volume::GuideTiles(cam.width), volume::GuideTiles(cam.height));
    volume::RaycastGuide(par::Host{}, View(depth), vo.truncation_m(), View(guide));
    long pixels = 0, differ = 0;
    std::vector<long> hits;  // per cast
    for (const auto& [pose, guided] : {std::pair{T, false}, std::pair{T, true}, std::pair{back, false}, std::pair{turned, false}}) {
      hits.push_back(0);
      volume::RaycastArgs a{cam, ToRigidTransform(pose), vo.raycast_near_m, vo.raycast_far_m};
      if (guided) a.start = View(guide);
      volume::Volume::Rendering one, two;
      for (auto* r : {&one, &two}) {
        r->vertex = Image<Float3>(cam.width, cam.height, Float3{-7, -7, -7});
        r->normal = Image<Float3>(cam.width, cam.height, Float3{-7, -7, -7});
        r->radiance = RadianceImage(cam.width, cam.height, Float3{-7, -7, -7});
        r->nr = Image<float>(cam.width, cam.height, -7.f);
        r->depth = DepthImage(cam.width, cam.height, -7.f);
      }
      auto views = [](volume::Volume::Rendering& r) {
        return volume::RenderingViews{View(r.vertex), View(r.normal), View(r.radiance), View(r.nr), View(r.depth)};
      };
      volume::RaycastInto(par::Host{}, vv, a, views(one));
      volume::RaycastInTwoPasses(par::Host{}, vv, a, views(two));
      const std::size_t n = std::size_t(cam.width) * std::size_t(cam.height);
      for (std::size_t i = 0; i < n; ++i) {
        pixels += 1;
        hits.back() += one.depth[i] > 0.f;
        differ += std::memcmp(&one.vertex[i], &two.vertex[i], sizeof(Float3)) != 0 ||
                  std::memcmp(&one.normal[i], &two.normal[i], sizeof(Float3)) != 0 ||
                  std::memcmp(&one.radiance[i], &two.radiance[i], sizeof(Float3)) != 0 ||
                  std::memcmp(&one.nr[i], &two.nr[i], sizeof(float)) != 0 ||
                  std::memcmp(&one.depth[i], &two.depth[i], sizeof(float)) != 0;
      }
    }
    std::printf("%s: %ld, %ld, %ld and %ld of %ld rays hit in the four casts; %ld pixels differ between one pass and two\n",
                volume::VoxelEncodingName(vo.encoding), hits[0], hits[1], hits[2], hits[3], pixels / 4, differ);
    EXPECT_EQ(differ, 0);
    for (int k = 0; k < 3; ++k) EXPECT_GT(hits[std::size_t(k)], pixels / 4 / 3) << k;  // many hits compared
    EXPECT_LT(hits[0], pixels / 4);                                                  // and misses beside them
    EXPECT_EQ(hits[3], 0);
  });
}

// The gradient from the 32 voxels read once (GradientOfVoxels) is the six samples' central
// differences (GradientOfSamples) to rounding wherever it is defined, for every encoding,
// at points around the surface; where a voxel it needs is unobserved it declines and
// Gradient takes the six samples.
// The ray cast's normal from the 32 voxels agrees with the six samples' differences, and
// the radiance read from the corners it found is the sampled radiance bit for bit.
TEST(Volume, GradientOfVoxelsMatchesTheSamplesAndItsCellTheRadiance) {
  const auto frames = Frames(6, sim::AeMode::kFixed);
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const Pose T = frames[0].T_world_camera.inverse() * frames.back().T_world_camera;
  const DepthImage depth = Metres(frames.back().depth);
  ForEachEncodingFused(frames, cam, [&](const volume::VolumeOptions& vo, const auto& vv) {
      using View = std::decay_t<decltype(vv)>;
      const volume::VoxelEncoding enc = vo.encoding;
      std::uint32_t state = 777u;
      auto uniform = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1u << 24); };
      long both = 0, samples_only = 0, voxels_only = 0, differ = 0, fell_back = 0, radiance_same = 0, with_radiance = 0;
      double worst = 0;
      for (int i = 0; i < 100000; ++i) {
        const int x = int(uniform() * 319.f), y = int(uniform() * 239.f);
        if (!(depth(x, y) > 0)) continue;
        const float z = depth(x, y) + (uniform() - 0.5f) * vo.truncation_m();
        const Float3 pc = cam.BackProject(float(x), float(y), z);
        const Eigen::Vector3d pw = T * Eigen::Vector3d(pc.x, pc.y, pc.z);
        const Float3 p{float(pw.x()), float(pw.y()), float(pw.z())};
        const typename View::BrickHint none;
        Float3 ga, gb, n;
        const typename View::Encoded* cell[8] = {};
        const bool a = vv.GradientOfVoxels(p, none, &ga, cell), b = vv.GradientOfSamples(p, none, &gb);
        if (a) {
          Float3 r1{-1, -1, -1}, r2{-2, -2, -2};
          float n1 = -1, n2 = -2;
          const bool s1 = vv.SampleRadianceOfCell(p, cell, &r1, &n1), s2 = vv.SampleRadiance(p, &r2, &n2);
          with_radiance += s2;
          radiance_same += s1 == s2 && (!s1 || (std::memcmp(&r1, &r2, sizeof r1) == 0 && std::memcmp(&n1, &n2, sizeof n1) == 0));
        }
        if (a && b) {
          ++both;
          // Rounding: the samples' own positions p +- one voxel round in grid units (hundreds
          // here, steps of 3e-5), so their weights are p's to about 1e-5 of a voxel.
          const double d = double(Length(ga - gb)) / std::max(1e-6, double(Length(gb)));
          worst = std::max(worst, d);
          differ += d > 1e-4;
        }
        samples_only += b && !a;
        voxels_only += a && !b;
        if (!a && b) {
          // Gradient declined by the voxels' way takes the samples' result.
          const float len = Length(gb);
          if (vv.Gradient(p, &n) && len >= 1e-6f && Length(n - gb / len) <= 1e-6f) ++fell_back;
        }
      }
      std::printf("%s: both ways at %ld points (largest difference %.2g of the gradient's length), only the samples at %ld, only the voxels at %ld\n",
                  volume::VoxelEncodingName(enc), both, worst, samples_only, voxels_only);
      EXPECT_GT(both, 50000);
      EXPECT_EQ(differ, 0);
      EXPECT_EQ(voxels_only, 0);  // where all 32 voxels are observed every sample is defined
      EXPECT_GT(samples_only, 0);
      EXPECT_EQ(fell_back, samples_only);
      EXPECT_GT(with_radiance, 10000);
      EXPECT_EQ(radiance_same, both + voxels_only);  // at every point the voxels' way took
  });
}

TEST(VoxelEncoding, HalfFloatsRoundTripAndRoundToNearestEven) {
  // Every finite half survives half -> float -> half bit for bit.
  int finite = 0;
  for (std::uint32_t h = 0; h < 65536; ++h) {
    if (((h >> 10) & 0x1f) == 31) continue;
    ++finite;
    ASSERT_EQ(volume::FloatToHalf(volume::HalfToFloat(std::uint16_t(h))), h) << "half 0x" << std::hex << h;
  }
  EXPECT_EQ(finite, 63488);
  // Exact values, the smallest subnormal, infinities and NaNs decoded.
  EXPECT_EQ(volume::HalfToFloat(0x3c00), 1.0f);
  EXPECT_EQ(volume::HalfToFloat(0xc000), -2.0f);
  EXPECT_EQ(volume::HalfToFloat(0x7bff), 65504.0f);
  EXPECT_EQ(volume::HalfToFloat(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(volume::HalfToFloat(0x8200), -std::ldexp(1.0f, -15));
  EXPECT_TRUE(std::isinf(volume::HalfToFloat(0x7c00)) && volume::HalfToFloat(0x7c00) > 0);
  EXPECT_TRUE(std::isinf(volume::HalfToFloat(0xfc00)) && volume::HalfToFloat(0xfc00) < 0);
  EXPECT_TRUE(std::isnan(volume::HalfToFloat(0x7e00)));
  EXPECT_TRUE(std::isnan(volume::HalfToFloat(0xfc01)));
  // Rounding: between two neighbouring halves, the nearer wins; a tie goes to the even one.
  const float one = volume::HalfToFloat(0x3c00), next = volume::HalfToFloat(0x3c01);
  EXPECT_EQ(volume::FloatToHalf(one + 0.49f * (next - one)), 0x3c00);
  EXPECT_EQ(volume::FloatToHalf(one + 0.51f * (next - one)), 0x3c01);
  EXPECT_EQ(volume::FloatToHalf(one + 0.5f * (next - one)), 0x3c00);  // tie, even mantissa
  const float n2 = volume::HalfToFloat(0x3c02);
  EXPECT_EQ(volume::FloatToHalf(next + 0.5f * (n2 - next)), 0x3c02);  // tie, rounds up to even
  EXPECT_EQ(volume::FloatToHalf(1e6f), 0x7c00);                        // overflow: infinity
  EXPECT_EQ(volume::FloatToHalf(3e-8f), 0x0001);                       // nearest subnormal
  // Relative error of normal values at most 2^-11.
  double worst = 0;
  for (float f = 1e-4f; f < 6e4f; f *= 1.0137f)
    worst = std::max(worst, std::abs(double(volume::HalfToFloat(volume::FloatToHalf(f))) / f - 1));
  EXPECT_LE(worst, 1.0 / 2048 + 1e-9);
  EXPECT_GT(worst, 1.0 / 8192);  // really quantised
}

// The compact encodings against the full one on the same 100-frame flicker sequence: fused
// with the true poses and exposures (the encoding alone decides the surface and radiance),
// then tracked end to end.
TEST(VoxelEncoding, CompactVoxelsKeepTheAccuracyOfFullOnes) {
  sim::SimOptions so;
  so.frames = 100;
  so.ae.mode = sim::AeMode::kFlicker;
  pipeline::SyntheticFrameSource src(so);
  const std::vector<pipeline::FrameInput> frames = pipeline::ReadAll(src);
  const sim::Scene scene = sim::Scene::Build(so.scene, so.seed);
  const SensorInfo& sensor = src.sensor();
  const radiometry::PcfTables pcf = radiometry::ComputePcf(*sensor.response, *sensor.noise);
  const PinholeCamera cam = sensor.camera;
  const Pose T0 = *frames[0].T_world_camera_true;
  struct Result {
    double ate_cm, mesh_mm, stops, within01;
    std::size_t bytes;
  };
  std::map<volume::VoxelEncoding, Result> res;
  for (auto enc : {volume::VoxelEncoding::kFull, volume::VoxelEncoding::kNoNr, volume::VoxelEncoding::kCompact}) {
    // 1. Fusion at the true poses and exposure ratios.
    volume::VolumeOptions vo;
    vo.encoding = enc;
    volume::Volume vol(vo);
    for (const auto& f : frames) {
      RadianceImage rad;
      Image<float> conf, maxconf;
      radiometry::ConvertFrame(f.color, *sensor.response, pcf, 1, rad, conf, maxconf);
      const DepthImage d = imaging::BilateralDepth(f.depth_m);
      const Image<Float3> n = imaging::NormalMap(imaging::VertexMap(d, cam));
      const Image<float> nr = nr::NormalizedRadiance(nr::Luminance(rad), {});
      volume::Volume::FrameInput in{&d, &n, &rad, &nr, &conf, &maxconf, cam, T0.inverse() * *f.T_world_camera_true,
                                    float(*frames[0].exposure_ms / *f.exposure_ms)};
      vol.Integrate(in);
    }
    const auto me = eval::CompareModel(mesh::ExtractMesh(vol), scene, T0);
    // 2. Tracking end to end.
    pipeline::PipelineOptions o;
    o.volume.encoding = enc;
    pipeline::Pipeline p(o, cam, sensor);
    std::vector<Pose> est, gt;
    for (const auto& f : frames) {
      est.push_back(p.Process(f).T_world_camera);
      gt.push_back(T0.inverse() * *f.T_world_camera_true);
    }
    const auto te = eval::CompareTrajectories(est, gt);
    res[enc] = {100 * te.ate_rmse_m, 1000 * me.mesh_median_distance_m, me.radiance_median_stops, me.within_01_stop,
                vol.bytes()};
    std::printf("encoding %2d B/voxel: tracked ATE %.2f cm; fused at true poses: mesh median %.2f mm, radiance "
                "median %.4f stops, %.1f %% within 0.1 stop, volume %.1f MiB\n",
                volume::EncodingBytes(enc), res[enc].ate_cm, res[enc].mesh_mm, res[enc].stops, 100 * res[enc].within01,
                double(res[enc].bytes) / (1024.0 * 1024.0));
  }
  const Result& full = res[volume::VoxelEncoding::kFull];
  EXPECT_LE(full.ate_cm, 2.0);
  for (auto enc : {volume::VoxelEncoding::kNoNr, volume::VoxelEncoding::kCompact}) {
    const Result& r = res[enc];
    EXPECT_LE(r.ate_cm, full.ate_cm + 0.3) << volume::EncodingBytes(enc) << " B";
    EXPECT_LE(r.mesh_mm, full.mesh_mm + 0.2) << volume::EncodingBytes(enc) << " B";
    EXPECT_LE(r.stops, full.stops + 0.005) << volume::EncodingBytes(enc) << " B";
    EXPECT_GE(r.within01, full.within01 - 0.01) << volume::EncodingBytes(enc) << " B";
    EXPECT_LT(r.bytes, full.bytes);
  }
  EXPECT_LT(res[volume::VoxelEncoding::kCompact].bytes, 0.5 * double(full.bytes));
}

// The built-in room, 300 frames, at the default voxel size: the volume has no bounds, so
// every surface the sensor measured is in the mesh (no cut planes). Against the largest
// fixed cube the engine used to need for this room (10 m over 512^3, 19.5 mm voxels, with a
// dense 64^3 brick index of 1 MiB), emulated here by the same voxel size: completeness (true
// surface within 2 cm of the mesh) at least as high, with less memory.
TEST(UnboundedVolume, RoomHasNoCutPlanesAndIsCompleteWithLessMemoryThanTheCube) {
  const auto frames = Frames(300, sim::AeMode::kFlicker);
  const Pose T0inv = frames[0].T_world_camera.inverse();
  // True surface samples the sensor measured (every 8th pixel of every 10th frame), in the
  // model's frame (the first camera's).
  const PinholeCamera cam = sim::SimCamera(320, 240);
  std::vector<Float3> truth;
  for (std::size_t i = 0; i < frames.size(); i += 10) {
    const Pose T = T0inv * frames[i].T_world_camera;
    for (int y = 0; y < 240; y += 8)
      for (int x = 0; x < 320; x += 8) {
        const float z = frames[i].depth_true(x, y);
        if (!(z > 0) || frames[i].depth(x, y) == 0) continue;
        const Float3 pc = cam.BackProject(float(x), float(y), z);
        const Vec3 pw = T * Vec3(pc.x, pc.y, pc.z);
        truth.push_back({float(pw.x()), float(pw.y()), float(pw.z())});
      }
  }
  struct Run {
    double completeness = 0, mib = 0, extent_m = 0;
    std::size_t bricks = 0, triangles = 0;
  };
  auto scan = [&](float voxel_m) {
    pipeline::PipelineOptions po;
    if (voxel_m > 0) po.volume.voxel_m = voxel_m;
    pipeline::Pipeline pipe(po, cam, sim::SyntheticSource(sim::SimOptions()).sensor());
    for (const auto& f : frames) pipe.Process(test::AsInput(f));
    const mesh::Mesh m = pipe.ExtractMesh();
    const volume::Volume& v = pipe.DownloadVolume();
    const auto box = v.Bounds();
    Run r;
    r.completeness = eval::SurfaceCompleteness(m, truth, 0.02).fraction();
    r.bricks = v.allocated_bricks();
    r.mib = double(v.bytes()) / (1 << 20);
    r.extent_m = std::max({box[1].x - box[0].x, box[1].y - box[0].y, box[1].z - box[0].z});
    r.triangles = m.triangles.size();
    EXPECT_FALSE(v.full()) << v.full_reason();
    return r;
  };
  const Run def = scan(0);
  const Run cube = scan(10.f / 512);
  // The fixed cube held the same bricks behind a dense index instead of hash tables.
  const double cube_mib = double(cube.bricks) * double(volume::VolumeOptions().brick_bytes()) / (1 << 20) + 1.0;
  std::printf("default %.1f mm voxels: completeness %.4f, %zu bricks, %.1f MiB, model %.2f m across, %zu triangles\n"
              "10 m / 512^3 cube (19.5 mm): completeness %.4f, %zu bricks, %.1f MiB with its index\n",
              1000 * volume::VolumeOptions().voxel_m, def.completeness, def.bricks, def.mib, def.extent_m, def.triangles,
              cube.completeness, cube.bricks, cube_mib);
  EXPECT_GT(def.extent_m, 6.0);  // wider than the old default 6 m cube: nothing cut at its faces
  // Completeness is a share of truth.size() samples, and each run tracks its own poses: "at
  // least as high" is judged within two standard errors of that share (the two runs' poses
  // differ by a fraction of a millimetre, which moves a handful of samples either way).
  const double se = std::sqrt(cube.completeness * (1 - cube.completeness) / double(truth.size()));
  std::printf("%zu samples: standard error of the completeness %.5f\n", truth.size(), se);
  EXPECT_GE(def.completeness, cube.completeness - 2 * se);
  EXPECT_GE(def.completeness, 0.95);
  EXPECT_LT(def.mib, cube_mib);
}

}  // namespace
}  // namespace hdrf

namespace hdrf::volume {
namespace {

// One voxel's update: in front of the surface it stores the signed distance over the
// truncation (capped at 1), weighted by |n.v|; radiance only near the surface, above tau0
// and with its confidence as weight; behind the truncation band nothing.
// The whole voxel decoded, updated and encoded again (the update as it was before voxels in
// free space kept their radiance's bits): the update of the decoded values as full floats,
// every field then encoded into V. The reference the stored voxels must equal.
template <typename V>
int IntegrateVoxelWhole(const volume::IntegrateArgs& a, int bx, int by, int bz, int i, V& stored) {
  volume::FullVoxel whole{stored.Decode()};
  const int done = volume::IntegrateVoxel(a, bx, by, bz, i, whole);
  if (done) stored.Store(whole.v);
  return done;
}

// Integration stores only the distance where the radiance does not change: every voxel of
// every brick a scan's frames touch, in each encoded form (full voxels store their floats
// whole either way), ends with exactly the bytes the whole decode-update-encode gives, frame
// after frame.
TEST(IntegrateVoxel, DistanceOnlyUpdatesKeepTheWholeUpdatesBytes) {
  const auto frames = Frames(8, sim::AeMode::kFlicker);
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const Pose T0inv = frames[0].T_world_camera.inverse();
  for (const auto enc : {volume::VoxelEncoding::kNoNr, volume::VoxelEncoding::kCompact}) {
    volume::VolumeOptions vo;
    vo.encoding = enc;
    volume::Volume vol(vo);
    volume::VisitEncoding(enc, [&](auto tag) {
      using V = decltype(tag);
      long voxels = 0, distance_only = 0, with_radiance = 0, differ = 0;
      for (std::size_t k = 0; k < frames.size(); ++k) {
        const auto& fr = frames[k];
        const DepthImage depth = Metres(fr.depth);
        const auto vmap = imaging::VertexMap(depth, cam);
        const auto n = imaging::NormalMap(vmap);
        Image<float> conf(320, 240, 0.7f), maxconf(320, 240, 0.8f), nrimg(320, 240, 0.3f);
        const RadianceImage r = fr.radiance.Clone();
        const Pose T = T0inv * fr.T_world_camera;
        // Each brick's voxels as they were, then the update both ways.
        const std::size_t bricks_before = vol.allocated_bricks();
        std::vector<V> before(bricks_before * 512);
        if (bricks_before > 0) std::memcpy(before.data(), vol.view<V>().pool, before.size() * sizeof(V));
        vol.Integrate({&depth, &n, &r, &nrimg, &conf, &maxconf, cam, T});
        if (k == 0) continue;  // the first frame's bricks are all new
        volume::IntegrateArgs a = volume::Volume::MakeIntegrateArgs(vo, cam, T, 1.f);
        a.depth = View(depth);
        a.normals = View(n);
        a.radiance = View(r);
        a.nr = View(nrimg);
        a.confidence = View(conf);
        a.max_confidence = View(maxconf);
        // The bricks the frame names (as Integrate finds them); the others stay as they were.
        std::set<std::uint64_t> named;
        const RigidTransform Twc = ToRigidTransform(T);
        for (int y = 0; y < 240; y += 2)
          for (int x = 0; x < 320; x += 2)
            volume::ForBricksAlongRay(a, Twc, x, y, [&](int bx, int by, int bz) { named.insert(volume::BrickKey(bx, by, bz)); });
        const volume::VolumeView<V> vv = vol.view<V>();
        for (std::size_t b = 0; b < bricks_before; ++b) {
          const auto c = vol.bricks()[b];
          const bool in_view = named.count(volume::BrickKey(c[0], c[1], c[2])) > 0;
          for (int i = 0; i < 512; ++i) {
            V whole = before[b * 512 + std::size_t(i)];
            const int done = in_view ? IntegrateVoxelWhole(a, c[0], c[1], c[2], i, whole) : 0;
            voxels += done != 0;
            distance_only += done == 1;
            with_radiance += done == 3;
            differ += std::memcmp(&whole, &vv.pool[b * 512 + std::size_t(i)], sizeof(V)) != 0;
          }
        }
      }
      std::printf("%s: %ld voxel updates (%ld distance only, %ld with radiance), %ld differ\n",
                  volume::VoxelEncodingName(enc), voxels, distance_only, with_radiance, differ);
      EXPECT_EQ(differ, 0);
      EXPECT_GT(distance_only, 100000);
      EXPECT_GT(with_radiance, 20000);
    });
  }
}

TEST(IntegrateVoxel, RunningMeansOfDistanceAndRadiance) {
  const PinholeCamera cam{8, 8, 8.f, 8.f, 3.5f, 3.5f};
  Image<float> depth(8, 8, 1.0f), conf(8, 8, 0.5f), maxconf(8, 8, 0.6f), nr(8, 8, 0.25f);
  Image<Float3> normals(8, 8, Float3{0, 0, -1});
  RadianceImage rad(8, 8, Float3{2, 4, 6});
  IntegrateArgs a{};
  a.depth = View(depth);
  a.normals = View(normals);
  a.radiance = View(rad);
  a.nr = View(nr);
  a.confidence = View(conf);
  a.max_confidence = View(maxconf);
  a.radiance_scale = 0.5f;
  a.cam = cam;
  a.T_camera_world = ToRigidTransform(Pose::Identity());
  a.voxel_m = 0.01f;
  a.trunc_m = 0.04f;
  a.max_weight = 64;
  a.max_radiance_weight = 64;
  a.tau0 = 0.1f;
  a.cos_tau1 = 0.25f;
  // Voxel (0,0,0) of the brick whose corner is at the origin: centre (0.005, 0.005, z).
  auto voxel_at = [&](float z) {
    Pose shift = Pose::Identity();  // the voxel's centre moved to depth z, as a camera offset
    shift.translation() = Vec3(0, 0, z - 0.005f);
    a.T_camera_world = ToRigidTransform(shift);
    FullVoxel v{};
    const int done = IntegrateVoxel(a, 0, 0, 0, 0, v);
    return std::pair<int, Voxel>{done, v.Decode()};
  };
  auto [done, v] = voxel_at(0.98f);  // 2 cm in front of the surface
  EXPECT_EQ(done, 3);
  EXPECT_NEAR(v.tsdf, 0.5f, 1e-4);
  EXPECT_NEAR(v.w, 1.f, 1e-3);  // |n.v| at the centre of the view
  EXPECT_NEAR(v.radiance.y, 2.f, 1e-6);  // 4 * the exposure scale 0.5
  EXPECT_NEAR(v.wr, 0.5f, 1e-6);
  std::tie(done, v) = voxel_at(0.90f);  // far in front: distance capped, no radiance
  EXPECT_EQ(done, 1);
  EXPECT_FLOAT_EQ(v.tsdf, 1.f);
  EXPECT_EQ(v.wr, 0.f);
  std::tie(done, v) = voxel_at(1.05f);  // behind the band
  EXPECT_EQ(done, 0);
  for (std::size_t i = 0; i < maxconf.size(); ++i) maxconf[i] = 0.05f;  // every channel below tau0
  std::tie(done, v) = voxel_at(0.99f);
  EXPECT_EQ(done, 1);
}

}  // namespace
}  // namespace hdrf::volume
