// The engine's parts against ground truth from the synthetic sensor and analytic shapes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "common/error.h"
#include "eval/eval.h"
#include "imaging/imaging.h"
#include "mesh/mesh.h"
#include "pipeline/frame_source.h"
#include "pipeline/pipeline.h"
#include "radiometry/pcf.h"
#include "sim/builtin_sensor.h"
#include "sim/synthetic_source.h"
#include "support/test_support.h"
#include "tracking/tracking.h"
#include "volume/volume.h"

namespace hdrf {
namespace {

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

std::vector<sim::SimFrame> Frames(int n, sim::AeMode ae, bool exact_depth = false,
                                  std::vector<double> list = {}) {
  sim::SimOptions o;
  o.frames = n;
  o.ae.mode = ae;
  o.ae.list_ms = list;
  o.depth.enabled = !exact_depth;
  sim::SyntheticSource src(o);
  std::vector<sim::SimFrame> out;
  while (!src.done()) out.push_back(src.Next());
  return out;
}

DepthImage Metres(const DepthRawImage& raw) {
  DepthImage d(raw.width(), raw.height());
  for (std::size_t i = 0; i < raw.size(); ++i) d[i] = raw[i] / 5000.f;
  return d;
}

TEST(Imaging, NormalizedRadianceIsExposureInvariant) {
  // One static view at 4 ms and 32 ms (8x apart).
  sim::SimOptions o;
  o.sweep = true;
  o.sweep_exposures_ms = {4, 32};
  o.sweep_repeats = 1;
  sim::SyntheticSource src(o);
  const sim::SimFrame a = src.Next(), b = src.Next();
  const SensorInfo s = src.sensor();
  const radiometry::PcfTables pcf = radiometry::ComputePcf(*s.response, *s.noise);
  RadianceImage ra, rb;
  Image<float> ca, cb, ma, mb;
  imaging::ConvertFrame(a.color, *s.response, pcf, 1, ra, ca, ma);
  imaging::ConvertFrame(b.color, *s.response, pcf, 1, rb, cb, mb);
  const Image<float> na = imaging::NormalizedRadiance(imaging::Luminance(ra), {});
  const Image<float> nb = imaging::NormalizedRadiance(imaging::Luminance(rb), {});
  std::vector<double> diff, mag;
  for (std::size_t i = 0; i < na.size(); ++i) {
    if (ca[i] < 0.3f || cb[i] < 0.3f) continue;  // both well exposed
    diff.push_back(std::abs(na[i] - nb[i]));
    mag.push_back(std::abs(na[i]));
  }
  ASSERT_GT(diff.size(), 5000u);
  std::printf("NR at 4 and 32 ms: median |difference| %.3f against median |NR| %.3f over %zu pixels\n",
              Median(diff), Median(mag), diff.size());
  EXPECT_LT(Median(diff), 0.1);
  EXPECT_GT(Median(mag), 0.3);  // the signal is real, not all zeros
  // Raw intensity is not invariant at all: the baseline's problem.
  double raw_diff = 0;
  for (std::size_t i = 0; i < a.color.size(); ++i) raw_diff += std::abs(a.color[i].g - b.color[i].g);
  EXPECT_GT(raw_diff / double(a.color.size()), 30.0);
}

TEST(Imaging, BilateralFilterSmoothsNoiseAndKeepsDepthEdges) {
  // A 1 m / 2 m step with 1 cm noise and a hole.
  DepthImage d(64, 48);
  std::uint32_t h = 12345;
  auto noise = [&h] {
    h = h * 1664525u + 1013904223u;
    return (float((h >> 8) & 0xffff) / 65535.f - 0.5f) * 0.0346f;  // uniform, sd 1 cm
  };
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) d(x, y) = (x < 32 ? 1.f : 2.f) + noise();
  d(10, 10) = 0;
  const DepthImage f = imaging::BilateralDepth(d);
  double in2 = 0, out2 = 0;
  int n = 0;
  float worst_edge = 0;
  for (int y = 4; y < 44; ++y)
    for (int x = 4; x < 60; ++x) {
      const float truth = x < 32 ? 1.f : 2.f;
      if (x >= 30 && x <= 33) worst_edge = std::max(worst_edge, std::abs(f(x, y) - truth));
      if (d(x, y) == 0) continue;
      in2 += std::pow(d(x, y) - truth, 2);
      out2 += std::pow(f(x, y) - truth, 2);
      ++n;
    }
  std::printf("bilateral: noise %.4f -> %.4f m; worst error next to the edge %.4f m\n", std::sqrt(in2 / n),
              std::sqrt(out2 / n), worst_edge);
  EXPECT_LT(std::sqrt(out2 / n), 0.5 * std::sqrt(in2 / n));
  EXPECT_LT(worst_edge, 0.03f);  // no blending across the 1 m step
  EXPECT_EQ(f(10, 10), 0.f);     // holes stay holes
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
  const float half = 0.5f * vo.size_m - 2 * vo.truncation_m();
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const float z = last.depth_true(x, y);
      if (!(z > 0)) continue;
      const Float3 pc = cam.BackProject(float(x), float(y), z);
      const Vec3 pw = T * Vec3(pc.x, pc.y, pc.z);
      if (pw.cwiseAbs().maxCoeff() > half) continue;  // outside the volume's cube
      ++inside;
      if (rend.depth(x, y) > 0) err.push_back(std::abs(rend.depth(x, y) - z));
    }
  const double coverage = double(err.size()) / double(inside);
  std::printf("ray cast vs true depth: median |error| %.4f m (voxel %.4f), coverage %.3f, %zu bricks\n",
              Median(err), vo.voxel_m(), coverage, vol.allocated_bricks());
  EXPECT_LT(Median(err), 0.25 * vo.voxel_m());
  EXPECT_GT(coverage, 0.9);
}

TEST(Tracking, FollowsTheCameraThroughFourfoldExposureJumps) {
  const auto frames = Frames(6, sim::AeMode::kList, false, {6, 24});
  const PinholeCamera cam = sim::SimCamera(320, 240);
  const SensorInfo s = sim::BuiltinXtionProfile();
  for (auto kind : {tracking::TrackerKind::kNr, tracking::TrackerKind::kNrIcp, tracking::TrackerKind::kIcp}) {
    pipeline::PipelineOptions po;
    po.tracker.kind = kind;
    pipeline::Pipeline pipe(po, cam, s);
    const Pose T0inv = frames[0].T_world_camera.inverse();
    double worst_t = 0, worst_r = 0;
    Pose prev_est = Pose::Identity(), prev_gt = Pose::Identity();
    for (const auto& f : frames) {
      pipeline::FrameInput in;
      in.color = f.color.Clone();
      in.depth_m = Metres(f.depth);
      const auto rep = pipe.Process(in);
      const Pose gt = T0inv * f.T_world_camera;
      // Error of the frame-to-frame motion (what one tracking step is responsible for).
      const Pose err = (prev_gt.inverse() * gt).inverse() * (prev_est.inverse() * rep.T_world_camera);
      prev_est = rep.T_world_camera;
      prev_gt = gt;
      worst_t = std::max(worst_t, se3::TranslationNorm(err));
      worst_r = std::max(worst_r, se3::RotationAngle(err) * 180 / M_PI);
      EXPECT_FALSE(rep.tracking.lost) << rep.tracking.why;
    }
    std::printf("%s: worst frame-to-frame motion error over 6 frames alternating 6 and 24 ms: "
                "%.2f mm, %.3f deg\n", tracking::TrackerName(kind), 1000 * worst_t, worst_r);
    // The model is one or two noisy frames thin here; over long scans errors are far smaller
    // (tests/cli ScanAccuracy).
    EXPECT_LT(worst_t, kind == tracking::TrackerKind::kNr ? 0.012 : 0.006);
    EXPECT_LT(worst_r, 0.3);
  }
}

TEST(Tracking, ExposureRatioFromMatchedPixels) {
  const auto frames = Frames(2, sim::AeMode::kList, false, {5, 20});
  const PinholeCamera cam = sim::SimCamera(320, 240);
  pipeline::PipelineOptions po;
  pipeline::Pipeline pipe(po, cam, sim::BuiltinXtionProfile());
  pipeline::FrameReport rep;
  for (const auto& f : frames) {
    pipeline::FrameInput in;
    in.color = f.color.Clone();
    in.depth_m = Metres(f.depth);
    in.exposure_ms = f.exposure_ms;
    rep = pipe.Process(in);
  }
  ASSERT_TRUE(rep.exposure_ratio_reported.has_value());
  EXPECT_DOUBLE_EQ(*rep.exposure_ratio_reported, 0.25);
  std::printf("exposure ratio: estimated %.4f, true 0.25 (%ld samples)\n", rep.exposure_ratio, rep.exposure_samples);
  EXPECT_NEAR(rep.exposure_ratio, 0.25, 0.005);
}

TEST(Mesh, SphereIsAccurateAndManifold) {
  volume::VolumeOptions vo;
  vo.resolution = 64;
  vo.size_m = 2.0f;
  volume::Volume vol(vo);
  // Integrate an analytic sphere seen from six directions (exact depth maps).
  const float R = 0.5f;
  const PinholeCamera cam{160, 120, 150.f, 150.f, 79.5f, 59.5f};
  const Vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& d : dirs) {
    const Vec3 eye = -1.6 * d;
    const Vec3 up = std::abs(d.z()) > 0.9 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
    const Vec3 r = d.cross(up).normalized(), dn = d.cross(r);
    Pose T = Pose::Identity();
    T.linear().col(0) = r;
    T.linear().col(1) = dn;
    T.linear().col(2) = d;
    T.translation() = eye;
    DepthImage depth(160, 120, 0.f);
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        const Float3 rc = cam.BackProject(float(x), float(y), 1.f);
        const Vec3 rw = T.linear() * Vec3(rc.x, rc.y, rc.z);
        const Vec3 u = rw.normalized();
        const double b = eye.dot(u), c = eye.squaredNorm() - R * R, disc = b * b - c;
        if (disc < 0) continue;
        const double t = -b - std::sqrt(disc);
        depth(x, y) = float(t / rw.norm());
      }
    const auto v = imaging::VertexMap(depth, cam);
    const auto n = imaging::NormalMap(v);
    Image<float> one(160, 120, 1.f);
    RadianceImage rad(160, 120, Float3{1, 2, 3});
    volume::Volume::FrameInput in{&depth, &n, &rad, &one, &one, &one, cam, T};
    vol.Integrate(in);
  }
  const mesh::Mesh m = mesh::ExtractMesh(vol);
  ASSERT_GT(m.triangles.size(), 1000u);
  std::vector<double> radial;
  for (const Float3& p : m.position) radial.push_back(std::abs(double(Length(p)) - R));
  const double med = Median(radial);
  std::sort(radial.begin(), radial.end());
  const double worst = radial[radial.size() * 99 / 100];
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  const long boundary = std::count_if(edges.begin(), edges.end(), [](const auto& e) { return e.second != 2; });
  const long over = std::count_if(edges.begin(), edges.end(), [](const auto& e) { return e.second > 2; });
  std::printf("edges used once or more than twice: %ld, more than twice: %ld\n", boundary, over);
  double outward = 0;
  for (std::size_t i = 0; i < m.position.size(); ++i) outward += Dot(m.normal[i], Normalized(m.position[i]));
  std::printf("sphere mesh: %zu vertices, radial error median %.4f m, 99th percentile %.4f m (voxel "
              "%.4f), %ld of %zu edges on a hole boundary, mean normal.radial %.3f\n", m.position.size(),
              med, worst, vo.voxel_m(), boundary, edges.size(), outward / double(m.position.size()));
  EXPECT_LT(med, 0.1 * vo.voxel_m());
  EXPECT_LT(worst, 0.5 * vo.voxel_m());
  EXPECT_EQ(over, 0);  // no edge shared by more than two triangles
  // Known gap: cubes with an unobserved corner are skipped, leaving small holes where the
  // six views meet at grazing angles (docs/engine.md); 420 of ~43k edges today.
  EXPECT_LT(double(boundary) / double(edges.size()), 0.02);
  EXPECT_GT(outward / double(m.position.size()), 0.99);
  EXPECT_FLOAT_EQ(m.radiance[0].y, 2.f);
}

TEST(Settings, ImpossibleVolumesAreRefusedByName) {
  volume::VolumeOptions o;
  o.size_m = 0;
  test::ExpectErrorContaining([&] { o.Check(); }, {"--volume-size", "positive"});
  o = {};
  o.resolution = 12;
  test::ExpectErrorContaining([&] { o.Check(); }, {"--volume-res", "multiple of 8"});
  o = {};
  o.resolution = 4096;
  o.max_memory_mb = 256;
  test::ExpectErrorContaining([&] { o.Check(); }, {"--volume-res", "MiB"});
  pipeline::PipelineOptions po;
  po.pcf = 7;
  test::ExpectErrorContaining([&] { po.Check(); }, {"--pcf"});
  SensorInfo no_response = sim::BuiltinXtionProfile();
  no_response.response.reset();
  test::ExpectErrorContaining([&] { pipeline::Pipeline p({}, sim::SimCamera(32, 24), no_response); },
                              {"response", "--response srgb"});
}

TEST(Eval, HornAlignmentRecoversARigidOffset) {
  std::vector<Pose> gt, est;
  Vec6 off;
  off << 0.3, -1.2, 0.5, 0.2, -0.4, 1.1;
  const Pose T = se3::Exp(off);
  for (int i = 0; i < 50; ++i) {
    Vec6 xi;
    xi << std::sin(0.1 * i), 0.05 * i, std::cos(0.07 * i), 0.01 * i, 0.02 * i, 0.0;
    gt.push_back(se3::Exp(xi));
    est.push_back(T * gt.back());
  }
  const auto e = eval::CompareTrajectories(est, gt);
  EXPECT_LT(e.ate_rmse_m, 1e-9);
  EXPECT_LT(e.rpe_trans_rmse_m, 1e-9);
  EXPECT_LT(se3::TranslationNorm(e.T_gt_est * T), 1e-9);
  // A known 1 cm error on one axis shows up as such.
  est[10].translation().x() += 0.01;
  EXPECT_NEAR(eval::CompareTrajectories(est, gt).ate_max_m, 0.01, 0.002);
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

TEST(VoxelEncoding, HalfFloatsRoundTripAndRoundToNearestEven) {
  // Every finite half survives half -> float -> half bit for bit.
  int finite = 0;
  for (std::uint32_t h = 0; h < 65536; ++h) {
    if (((h >> 10) & 0x1f) == 31) continue;
    ++finite;
    ASSERT_EQ(volume::FloatToHalf(volume::HalfToFloat(std::uint16_t(h))), h) << "half 0x" << std::hex << h;
  }
  EXPECT_EQ(finite, 63488);
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
// then tracked end to end (docs/benchmarks.md records the table).
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
      imaging::ConvertFrame(f.color, *sensor.response, pcf, 1, rad, conf, maxconf);
      const DepthImage d = imaging::BilateralDepth(f.depth_m);
      const Image<Float3> n = imaging::NormalMap(imaging::VertexMap(d, cam));
      const Image<float> nr = imaging::NormalizedRadiance(imaging::Luminance(rad), {});
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

}  // namespace
}  // namespace hdrf
