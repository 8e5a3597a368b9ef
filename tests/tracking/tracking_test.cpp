#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include <omp.h>
#include <cstring>

#include <Eigen/Dense>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "pipeline/pipeline.h"
#include "sim/builtin_sensor.h"
#include "tracking/gn_step.h"
#include "tracking/term_batch.h"
#include "tracking/tracking.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

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

// The CPU's normal equations are summed in fixed row chunks added in chunk order: the same
// bits whatever the number of threads (and so whichever thread takes which chunk).
TEST(Tracking, NormalEquationsAreTheSameBitsForAnyNumberOfThreads) {
  const auto frames = Frames(2, sim::AeMode::kFixed);
  const PinholeCamera cam = sim::SimCamera(320, 240);
  auto grey = [&](const auto& f) {
    Image<float> g(320, 240);
    for (int y = 0; y < 240; ++y)
      for (int x = 0; x < 320; ++x) {
        const Rgb8 c = f.color(x, y);
        g(x, y) = (float(c.r) + float(c.g) + float(c.b)) / 765.f;
      }
    return g;
  };
  const DepthImage d0 = Metres(frames[0].depth), d1 = Metres(frames[1].depth);
  const Image<float> ones(320, 240, 1.f);
  const tracking::Live ref_frame = tracking::MakeLive(d0, grey(frames[0]), ones, cam, 3, 0.1f);
  const tracking::Reference ref = tracking::MakeReference(ref_frame.levels[0].vertex_c, ref_frame.levels[0].normal_c,
                                                          ref_frame.levels[0].intensity, cam, 3, Pose::Identity());
  const tracking::Live live = tracking::MakeLive(d1, grey(frames[1]), ones, cam, 3, 0.1f);
  const Pose T = frames[0].T_world_camera.inverse() * frames[1].T_world_camera;
  tracking::TrackerOptions o;
  o.kind = tracking::TrackerKind::kNrIcp;
  const int threads = omp_get_max_threads();
  std::vector<tracking::GnSystem> sums;
  for (int n : {1, 2, 3, 7}) {
    omp_set_num_threads(n);
    for (int l = 0; l < 3; ++l)
      sums.push_back(tracking::AccumulateCpu(ref.levels[std::size_t(l)].view(), ref.T_world_camera,
                                             live.levels[std::size_t(l)].view(), T, o));
  }
  omp_set_num_threads(threads);
  for (std::size_t k = 3; k < sums.size(); ++k)
    EXPECT_EQ(std::memcmp(sums[k].v, sums[k % 3].v, sizeof sums[k].v), 0) << "level " << k % 3 << ", run " << k / 3;
  EXPECT_GT(sums[0].icp_n(), 10000);  // both terms were summed over many pixels
  EXPECT_GT(sums[0].photo_n(), 10000);
  // The CPU sums a row's ICP terms and its photometric terms each in two passes (every
  // pixel's projection, four pixels at a time, then the terms at the pixels found), in runs of
  // 256 pixels (a 320-pixel row takes two): the bits of IcpTerm and PhotoTerm pixel by pixel,
  // in chunks of four rows added in chunk order.
  auto pixel_by_pixel = [](int w, int h, const auto& term) {
    tracking::GnSystem sum;
    for (int y0 = 0; y0 < h; y0 += 4) {
      tracking::GnSystem chunk;
      {
        tracking::TermBatch batch(chunk);
        for (int y = y0; y < std::min(h, y0 + 4); ++y)
          for (int x = 0; x < w; ++x) term(x, y, batch);
      }
      sum.Merge(chunk);
    }
    return sum;
  };
  for (const auto kind : {tracking::TrackerKind::kIcp, tracking::TrackerKind::kNr}) {
    o.kind = kind;
    const bool icp = kind == tracking::TrackerKind::kIcp;
    for (int l = 0; l < 3; ++l) {
      const tracking::ReferenceView rv = ref.levels[std::size_t(l)].view();
      const tracking::LiveView lv = live.levels[std::size_t(l)].view();
      tracking::GnSystem rows = tracking::AccumulateCpu(rv, ref.T_world_camera, lv, T, o);
      const tracking::IcpArgs ia = tracking::MakeIcpArgs(rv, ref.T_world_camera, lv, T, o);
      const tracking::PhotoArgs pa = tracking::MakePhotoArgs(rv, lv, T, o);
      tracking::GnSystem one_by_one =
          icp ? pixel_by_pixel(lv.cam.width, lv.cam.height,
                               [&](int x, int y, tracking::TermBatch& b) { tracking::IcpTerm(ia, x, y, b); })
              : pixel_by_pixel(rv.cam.width, rv.cam.height,
                               [&](int x, int y, tracking::TermBatch& b) { tracking::PhotoTerm(pa, x, y, b); });
      EXPECT_EQ(std::memcmp(rows.v, one_by_one.v, sizeof rows.v), 0) << (icp ? "icp" : "photometric") << ", level " << l;
      const std::size_t n = icp ? std::size_t(rows.icp_n()) : std::size_t(rows.photo_n());
      EXPECT_GT(n, l == 0 ? 10000u : 100u);
      EXPECT_EQ(n, icp ? std::size_t(one_by_one.icp_n()) : std::size_t(one_by_one.photo_n()));
    }
  }
}

}  // namespace
}  // namespace hdrf

namespace hdrf::tracking {
namespace {

// Normal equations of a view whose truth is the identity pose: five directions fixed with
// weight `strong`, and x with weight `weak` by a term biased `bias` metres.
Accumulator OneWeakDirection(double strong, double weak, double bias) {
  return [=](int, const Pose& T) {
    const Vec6 e = se3::Log(T);
    GnSystem acc;
    for (int i = 0; i < 6; ++i) {
      double J[6] = {0, 0, 0, 0, 0, 0};
      J[i] = 1;
      if (i == 0) acc.Add(J, e(0) - bias, weak);
      else acc.Add(J, e(i), strong);
    }
    acc.icp_n() = 1000;
    acc.icp_w() = 1000;
    return acc;
  };
}

// The motion prior: a view that constrains five directions of the pose strongly and one
// (x: along a flat, untextured wall) only through a weak, biased term. Without the prior the
// pose slides 5 cm along x to that term's minimum; with it the pose keeps to the prediction
// along x, and the strongly constrained directions still go where the data put them, even
// where the prediction was 2 cm off along z.
TEST(TrackPrior, HoldsTheLooseDirectionAndLeavesTheConstrainedOnes) {
  const double kStrong = 1e8, kWeak = 1e3, kBias = 0.05;
  const Accumulator accumulate = OneWeakDirection(kStrong, kWeak, kBias);
  TrackerOptions o;
  o.max_jump_m = 1;
  Pose predicted = Pose::Identity();
  predicted.translation() = Vec3(0, 0, 0.02);
  const TrackResult free = Track(accumulate, 3, 1000, predicted, o);
  const MotionPrior one{predicted, 1}, four{predicted, 4};
  const TrackResult held = Track(accumulate, 3, 1000, predicted, o, &one);
  // A prediction over four frame intervals (frames dropped) is trusted less: it holds less.
  const TrackResult looser = Track(accumulate, 3, 1000, predicted, o, &four);
  const Vec3 tf = free.T_world_camera.translation(), th = held.T_world_camera.translation();
  const double x4 = looser.T_world_camera.translation().x();
  std::printf("without the prior x %.2f mm, z %.4f mm; with it x %.2f mm, z %.4f mm; over 4 frames x %.2f mm\n",
              1e3 * tf.x(), 1e3 * tf.z(), 1e3 * th.x(), 1e3 * th.z(), 1e3 * x4);
  EXPECT_GT(x4, 3 * th.x());
  EXPECT_LT(x4, tf.x());
  EXPECT_NEAR(tf.x(), kBias, 0.002);       // slid to the weak term's minimum
  EXPECT_LT(std::abs(th.x()), 0.2 * kBias);  // held near the prediction
  EXPECT_LT(std::abs(th.z()), 1e-4);         // the data win where they constrain the pose
  EXPECT_LT(std::abs(th.y()), 1e-4);
  EXPECT_LT(se3::RotationAngle(held.T_world_camera), 1e-4);
}

// The weak-direction floor: a view whose weakest direction (x, a wall slid along) the data
// still fix a hundred times better than the prior, but ten thousand times worse than their
// strongest, and biased by 5 cm (as on the hall and the flicker room without the floor,
// where poses slide 1-17 cm a frame with the point-to-surface error at its usual). The prior
// alone cannot hold such a direction; with the floor the prediction holds it, and the
// strongly fixed directions still go where the data put them.
TEST(TrackPrior, WeakDirectionOfAStrongViewIsHeldToThePrediction) {
  const double kStrong = 1e10, kWeak = 1e6, kBias = 0.05;
  const Accumulator accumulate = OneWeakDirection(kStrong, kWeak, kBias);
  Pose predicted = Pose::Identity();
  predicted.translation() = Vec3(0, 0, 0.02);
  const MotionPrior prior{predicted, 1};
  TrackerOptions off;
  off.max_jump_m = 1;
  off.weak_info_floor = 0;
  TrackerOptions on = off;
  on.weak_info_floor = TrackerOptions{}.weak_info_floor;
  const TrackResult slid = Track(accumulate, 3, 1000, predicted, off, &prior);
  const TrackResult held = Track(accumulate, 3, 1000, predicted, on, &prior);
  const Vec3 ts = slid.T_world_camera.translation(), th = held.T_world_camera.translation();
  std::printf("weakest direction 1e-4 of the strongest: prior alone x %.2f mm; with the floor x %.2f mm, z %.4f mm "
              "(prediction 20 mm off in z)\n",
              1e3 * ts.x(), 1e3 * th.x(), 1e3 * th.z());
  EXPECT_GT(ts.x(), 0.9 * kBias);            // the prior alone: slid nearly all the way
  EXPECT_LT(std::abs(th.x()), 0.1 * kBias);  // the floor: held near the prediction
  EXPECT_LT(std::abs(th.z()), 1e-4);         // the data still win where they are strong
  EXPECT_LT(se3::RotationAngle(held.T_world_camera), 1e-4);
  int per_level = 0;
  for (int n : held.level_iterations) per_level += n;
  EXPECT_EQ(per_level, held.iterations);
  EXPECT_GT(held.level_iterations[0], 0);
}

// One ICP term: a live point 1 cm in front of a reference plane facing the camera adds the
// point-to-plane residual with the Jacobian of the plane's normal; a normal turned away
// beyond the angle gate, or a point beyond the distance gate, adds nothing.
// The step as the tracker took it with Eigen before it was written once for both devices
// (gn_step.h): the reference the plain-double step must reproduce.
Pose EigenStep(const tracking::GnSystem& acc, const Pose& T, const Pose& predicted, double sigma_m, double sigma_rad,
               double floor, bool* raised) {
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Vec6d = Eigen::Matrix<double, 6, 1>;
  Mat6 H;
  Vec6d g;
  for (int i = 0, k = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j, ++k) H(i, j) = H(j, i) = acc.v[k];
    g(i) = acc.v[tracking::GnSystem::kH + i];
  }
  const Vec6 e = se3::Log(predicted.inverse() * T);
  Vec6d sw, ew;
  for (int i = 0; i < 6; ++i) {
    sw(i) = i < 3 ? sigma_m : sigma_rad;
    ew(i) = e(i) / sw(i);
  }
  const Mat6 Hw = sw.asDiagonal() * H * sw.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Mat6> es(Hw);
  *raised = false;
  for (int k = 0; k < 6; ++k) {
    const double add = floor * es.eigenvalues()(5) - es.eigenvalues()(k);
    if (!(add > 0)) continue;
    *raised = true;
    const Vec6d v = es.eigenvectors().col(k);
    const Vec6d u = v.cwiseQuotient(sw);
    H += add * u * u.transpose();
    g += add * u * v.dot(ew);
  }
  for (int i = 0; i < 6; ++i) {
    const double lambda = 1.0 / (sw(i) * sw(i));
    H(i, i) += lambda;
    g(i) += lambda * e(i);
  }
  const Mat6 Hd = H + 1e-6 * Mat6::Identity() * H.trace() / 6.0;
  const Vec6d xi = Hd.ldlt().solve(-g);
  return se3::Orthonormalized(T * se3::Exp(Vec6(xi)));
}

// n symmetric 6x6 matrices (row-major) for SymmetricEigen6's test: Q diag(lam) Q^T with a
// random rotation Q and eigenvalues spread over up to 12 decades (the whitened normal
// equations of a wall seen head on), some with repeated or nearly repeated eigenvalues, some
// already diagonal or with zero entries, and plain sums of outer products of random vectors.
std::vector<std::array<double, 36>> SymmetricSixes(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 36>> out;
  for (int m = 0; m < n; ++m) {
    std::array<double, 36> A{};
    const int kind = m % 5;
    if (kind == 4) {  // outer products
      for (int r = 0; r < 1 + m % 9; ++r) {
        double v[6];
        for (double& x : v) x = g(rng);
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j) A[std::size_t(6 * i + j)] += v[i] * v[j];
      }
      out.push_back(A);
      continue;
    }
    double lam[6];
    for (int k = 0; k < 6; ++k) lam[k] = std::pow(10.0, 12.0 * u(rng) - 6.0);
    if (kind == 1) lam[1] = lam[0], lam[3] = lam[2] * (1 + 1e-13);  // repeated, nearly repeated
    // Q: Gram-Schmidt of a random matrix (identity for the diagonal kind).
    double Q[36];
    for (double& x : Q) x = g(rng);
    if (kind == 2)
      for (int k = 0; k < 36; ++k) Q[k] = k % 7 == 0 ? 1.0 : 0.0;
    for (int c = 0; c < 6; ++c) {
      for (int p = 0; p < c; ++p) {
        double d = 0;
        for (int r = 0; r < 6; ++r) d += Q[6 * r + c] * Q[6 * r + p];
        for (int r = 0; r < 6; ++r) Q[6 * r + c] -= d * Q[6 * r + p];
      }
      double l = 0;
      for (int r = 0; r < 6; ++r) l += Q[6 * r + c] * Q[6 * r + c];
      for (int r = 0; r < 6; ++r) Q[6 * r + c] /= std::sqrt(l);
    }
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        double s = 0;
        for (int k = 0; k < 6; ++k) s += Q[6 * i + k] * lam[k] * Q[6 * j + k];
        A[std::size_t(6 * i + j)] = s;
      }
    for (int i = 0; i < 6; ++i)  // exactly symmetric
      for (int j = 0; j < i; ++j) A[std::size_t(6 * i + j)] = A[std::size_t(6 * j + i)];
    if (kind == 3) A[1] = A[6] = 0, A[2 * 6 + 5] = A[5 * 6 + 2] = 0;  // zero entries to skip
    out.push_back(A);
  }
  return out;
}

// SymmetricEigen6 (gn_step.h: the weak directions' decomposition, the same code on both
// devices) against Eigen's solver: ascending eigenvalues within 1e-12 of the largest,
// orthonormal eigenvectors with A v = lambda v to 1e-12 of the largest, on 500 matrices
// (eigenvalues over 12 decades, repeated ones, diagonal ones, zero entries, outer products).
// Updating V's rows where its columns are meant failed it (|A v - lambda v| 1.1).
TEST(GaussNewtonStep, SymmetricEigen6DecomposesAsEigenDoes) {
  const auto mats = SymmetricSixes(500, 11);
  double worst_value = 0, worst_vector = 0, worst_orth = 0;
  for (const auto& A : mats) {
    double lam[6], V[36];
    tracking::SymmetricEigen6(A.data(), lam, V);
    Eigen::Matrix<double, 6, 6> M;
    for (int i = 0; i < 36; ++i) M(i / 6, i % 6) = A[std::size_t(i)];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(M);
    const double top = std::max(std::abs(es.eigenvalues()(0)), std::abs(es.eigenvalues()(5)));
    for (int k = 0; k < 6; ++k) {
      if (k > 0) ASSERT_LE(lam[k - 1], lam[k]);
      worst_value = std::max(worst_value, std::abs(lam[k] - es.eigenvalues()(k)) / top);
      Eigen::Matrix<double, 6, 1> v;
      for (int r = 0; r < 6; ++r) v(r) = V[6 * r + k];
      worst_vector = std::max(worst_vector, (M * v - lam[k] * v).norm() / top);
      for (int j = 0; j < 6; ++j) {
        double d = 0;
        for (int r = 0; r < 6; ++r) d += V[6 * r + k] * V[6 * r + j];
        worst_orth = std::max(worst_orth, std::abs(d - (j == k ? 1.0 : 0.0)));
      }
    }
  }
  std::printf("[ figures  ] 500 matrices: eigenvalues within %.2g of the largest, |A v - lambda v| %.2g, "
              "orthonormal to %.2g\n", worst_value, worst_vector, worst_orth);
  EXPECT_LT(worst_value, 1e-12);
  EXPECT_LT(worst_vector, 1e-12);
  EXPECT_LT(worst_orth, 1e-12);
}

TEST(GaussNewtonStep, PlainDoubleStepMatchesTheEigenSolveWithAndWithoutTheWeakFloor) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n01(0, 1);
  auto twist = [&](double st, double sr) {
    Vec6 x;
    for (int i = 0; i < 6; ++i) x(i) = n01(rng) * (i < 3 ? st : sr);
    return x;
  };
  int raised = 0, trials = 400;
  double worst_t = 0, worst_r = 0;
  for (int trial = 0; trial < trials; ++trial) {
    // A system of 60 terms; in half the trials one direction is nearly unconstrained (a wall
    // slid along), so that the prior's floor is raised there.
    tracking::GnSystem acc;
    const bool weak = trial % 2 == 0;
    Vec6 weak_dir = twist(1, 1).normalized();
    for (int k = 0; k < 60; ++k) {
      Vec6 j = twist(30, 3);
      if (weak) j -= j.dot(weak_dir) * (1 - 1e-4) * weak_dir;
      double J[6];
      for (int i = 0; i < 6; ++i) J[i] = j(i);
      tracking::AddRobustTerm(acc, J, n01(rng) * 0.01, 1.0, 1.345, 27);
    }
    const Pose T = se3::Exp(twist(0.5, 0.8)), predicted = T * se3::Exp(twist(0.01, 0.01));
    const double spans = 1 + trial % 3;
    tracking::TrackerOptions o;
    const tracking::MotionPrior prior{predicted, spans};
    const tracking::StepPrior sp = tracking::MakeStepPrior(o, &prior);
    bool r = false;
    const Pose want = EigenStep(acc, T, predicted, sp.sigma_m, sp.sigma_rad, sp.floor, &r);
    raised += r;
    tracking::PoseD got = tracking::ToPoseD(T);
    const int out = tracking::GnStep(acc, sp, &got);
    ASSERT_TRUE(out == tracking::kStepTaken || out == tracking::kStepConverged) << "trial " << trial;
    const Pose d = want.inverse() * tracking::FromPoseD(got);
    worst_t = std::max(worst_t, se3::TranslationNorm(d));
    worst_r = std::max(worst_r, se3::RotationAngle(d));
  }
  std::printf("%d of %d steps raised the prior along a weak direction; worst difference from Eigen %.2g m, %.2g rad\n",
              raised, trials, worst_t, worst_r);
  EXPECT_GE(raised, trials / 4);
  EXPECT_LE(worst_t, 1e-12);
  EXPECT_LE(worst_r, 1e-12);
  // Too few terms: no step, the pose kept.
  tracking::GnSystem few;
  double J[6] = {1, 0, 0, 0, 0, 0};
  for (int k = 0; k < 11; ++k) tracking::AddRobustTerm(few, J, 0.1, 1.0, 1.345, 27);
  tracking::PoseD keep = tracking::ToPoseD(se3::Exp(twist(0.3, 0.3)));
  const tracking::PoseD before = keep;
  EXPECT_EQ(tracking::GnStep(few, tracking::StepPrior{}, &keep), tracking::kStepTooFew);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(keep.R[k], before.R[k]);
}

TEST(GaussNewtonStep, PlainDoubleExpLogAndOrthonormalisationMatchSe3) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst_log = 0, worst_exp = 0;
  // Angles from 1e-12 to just under pi, with every axis (Shepperd's method switches branch
  // on the trace and the largest diagonal entry).
  for (int k = 0; k < 3000; ++k) {
    Eigen::Vector3d axis(u(rng), u(rng), u(rng));
    axis.normalize();
    const double angle = k % 3 == 0 ? std::pow(10.0, -12 + 12 * std::abs(u(rng))) : 3.14159 * std::abs(u(rng));
    Vec6 xi;
    xi << u(rng), u(rng), u(rng), axis.x() * angle, axis.y() * angle, axis.z() * angle;
    const Pose T = se3::Exp(xi);
    double x[6];
    for (int i = 0; i < 6; ++i) x[i] = xi(i);
    const Pose Te = tracking::FromPoseD(tracking::ExpTwist(x));
    worst_exp = std::max(worst_exp, (T.matrix() - Te.matrix()).cwiseAbs().maxCoeff());
    double back[6];
    tracking::LogTwist(tracking::ToPoseD(T), back);
    const Vec6 want = se3::Log(T);
    for (int i = 0; i < 6; ++i) worst_log = std::max(worst_log, std::abs(back[i] - want(i)));
    // A rotation a little off orthonormal comes back as se3::Orthonormalized makes it.
    Pose skew = T;
    skew.linear()(0, 1) += 1e-7 * u(rng);
    skew.linear()(2, 0) += 1e-7 * u(rng);
    const Pose o1 = se3::Orthonormalized(skew), o2 = tracking::FromPoseD(tracking::OrthonormalizedD(tracking::ToPoseD(skew)));
    worst_exp = std::max(worst_exp, (o1.matrix() - o2.matrix()).cwiseAbs().maxCoeff());
  }
  std::printf("worst difference from se3: exp/orthonormalise %.2g, log %.2g\n", worst_exp, worst_log);
  EXPECT_LE(worst_exp, 1e-14);
  EXPECT_LE(worst_log, 1e-9);
}

// The CPU's batched sums against terms added one at a time: for batches of 1 to 3 x 128 + 3
// terms (partly filled last groups, batches emptied when full and at the end), the normal
// equations agree to rounding, the robust sums and counts exactly; each lane's sum is a
// quarter of the terms, so leaving out a lane, a padded term or a full batch fails.
TEST(TermBatch, SumsAsTermsAddedOneAtATime) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  for (int count : {1, 2, 3, 4, 5, 127, 128, 129, 255, 387}) {
    for (int first : {27, 28}) {
      tracking::GnSystem one, batched;
      {
        tracking::TermBatch batch(batched);
        for (int k = 0; k < count; ++k) {
          double J[6];
          for (double& j : J) j = n01(rng) * 10 + 3;  // all sums grow, none cancels
          const double r = n01(rng) * 0.05, s = 1 + 0.1 * std::abs(n01(rng));
          tracking::AddRobustTerm(one, J, r, s, 0.04, first);  // a small Huber k: many terms down-weighted
          AddRobustTerm(batch, J, r, s, 0.04, first);
        }
      }
      double worst = 0;
      for (int i = 0; i < tracking::GnSystem::kH + tracking::GnSystem::kG; ++i)
        worst = std::max(worst, std::abs(one.v[i] - batched.v[i]) / std::max(1e-300, std::abs(one.v[i])));
      EXPECT_LE(worst, 1e-12) << count << " terms";
      EXPECT_GT(std::abs(batched.v[0]), 0) << count << " terms";
      for (int i = tracking::GnSystem::kH + tracking::GnSystem::kG; i < tracking::GnSystem::kSize; ++i)
        EXPECT_EQ(one.v[i], batched.v[i]) << count << " terms, sum " << i;
      EXPECT_EQ(batched.v[first + 4], count);
    }
  }
}

TEST(IcpTerm, PointToPlaneResidualAndGates) {
  const PinholeCamera cam{4, 4, 4.f, 4.f, 1.5f, 1.5f};
  Image<Float3> live_v(4, 4), live_n(4, 4, Float3{0, 0, -1}), ref_v(4, 4), ref_n(4, 4, Float3{0, 0, -1});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      live_v(x, y) = cam.BackProject(float(x), float(y), 0.99f);
      ref_v(x, y) = cam.BackProject(float(x), float(y), 1.0f);
    }
  TrackerOptions o;
  const Pose I = Pose::Identity();
  const ReferenceView ref{cam, View(ref_v), View(ref_n), {}};
  const LiveView live{cam, View(live_v), View(live_n), {}, {}, {}, {}};
  IcpArgs a = MakeIcpArgs(ref, I, live, I, o);
  GnSystem acc;
  ASSERT_TRUE(IcpTerm(a, 1, 1, acc));
  EXPECT_EQ(acc.icp_n(), 1.0);
  // r = n.(p - m) = (0,0,-1).(0,0,-0.01) = 0.01 m, within the Huber threshold (1.345 sigma):
  // full weight, and the squared residual r^2 in m^2.
  EXPECT_DOUBLE_EQ(acc.icp_w(), 1.0);
  EXPECT_NEAR(acc.icp_r2(), 1e-4, 1e-7);
  live_n(1, 1) = Float3{0, -1, 0};  // 90 degrees off the reference normal
  GnSystem none;
  EXPECT_FALSE(IcpTerm(a, 1, 1, none));
  live_n(1, 1) = Float3{0, 0, -1};
  live_v(1, 1) = cam.BackProject(1.f, 1.f, 0.8f);  // 20 cm off: beyond icp_max_dist_m
  EXPECT_FALSE(IcpTerm(a, 1, 1, none));
  EXPECT_EQ(none.icp_n(), 0.0);
}

}  // namespace
}  // namespace hdrf::tracking
