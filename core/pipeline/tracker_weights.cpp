// How the tracker's terms are weighed frame by frame: the frame's sampled depth (whose median
// the point-to-plane scale holds at, TrackerOptions::depth_noise_scaling) and nr+icp's
// photometric share by its agreement with the depth (TrackerOptions::photo_agreement).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "pipeline/backend.h"
#include "pipeline/pipeline.h"

namespace hdrf::pipeline {

namespace {
// nr+icp: how far the photometric term may pull the pose off the depth's own optimum
// (Pipeline::WeighPhotometric), and the least share it keeps before it is dropped.
constexpr double kPhotoPullM = 0.001, kPhotoPullRad = 0.05 * 3.14159265358979 / 180.0;
constexpr double kMinPhotoShare = 0.05;
constexpr double kStrongDirection = 1e-2;  // ...of the strongest direction's information
constexpr double kPriorScaleM = 0.01, kPriorScaleRad = 3.14159265358979 / 180.0;  // 1 cm, 1 degree
}  // namespace

Pipeline::DepthSamples Pipeline::SampleDepth(const DepthImage& depth_m, float far_m) {
  long with_depth = 0, beyond = 0, samples = 0;
  std::vector<float> depths;
  depths.reserve(std::size_t(depth_m.width() / 4 + 1) * std::size_t(depth_m.height() / 4 + 1));
  for (int y = 0; y < depth_m.height(); y += 4)
    for (int x = 0; x < depth_m.width(); x += 4) {
      const float z = depth_m(x, y);
      ++samples;
      with_depth += z > 0;
      beyond += z > far_m;
      if (z > 0 && std::isfinite(z)) depths.push_back(z);
    }
  DepthSamples d;
  d.share = samples > 0 ? double(with_depth) / double(samples) : 0.0;
  d.beyond_far = with_depth > 0 ? double(beyond) / double(with_depth) : 0.0;
  if (!depths.empty()) {
    auto mid = depths.begin() + std::ptrdiff_t(depths.size() / 2);
    std::nth_element(depths.begin(), mid, depths.end());
    d.median_m = double(*mid);
  }
  return d;
}

void Pipeline::WeighPhotometric(Backend& b, const tracking::TrackerOptions& topt, const Pose& start,
                                const tracking::MotionPrior& prior, tracking::TrackResult* r) {
  // At the pose the joint solve found, each term's own Gauss-Newton step on its own: where the
  // colour fits the depth (registered, with a response that holds), both are at their optimum
  // and neither wants to move; where it does not (colour a few pixels off the depth, an
  // assumed response), the photometric term has pulled the pose off the depth's optimum, and
  // the depth's own step measures how far. Beyond kPhotoPullM / kPhotoPullRad the photometric
  // term's share is cut and the finest level solved again; below kMinPhotoShare it is dropped.
  tracking::TrackerOptions ti = topt;
  ti.kind = tracking::TrackerKind::kIcp;
  // The depth's own step, along the directions it fixes: in units of 1 cm and 1 degree (as
  // the tracker's weak directions are judged), those whose information is under
  // kStrongDirection of the strongest one's (a wall slid along) are left out: there the
  // photometric term is what holds the pose, and no pull can be told from the depth's noise.
  const tracking::GnSystem si = b.Accumulate(0, r->T_world_camera, ti);
  if (si.v[31] < 50) return;  // the depth fixes nothing alone: the joint pose stands
  Eigen::Matrix<double, 6, 6> H;
  Eigen::Matrix<double, 6, 1> g, sw;
  for (int i = 0, k = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j, ++k) H(i, j) = H(j, i) = si.v[k];
    g(i) = si.v[tracking::GnSystem::kH + i];
  }
  sw << kPriorScaleM, kPriorScaleM, kPriorScaleM, kPriorScaleRad, kPriorScaleRad, kPriorScaleRad;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(sw.asDiagonal() * H * sw.asDiagonal());
  if (es.info() != Eigen::Success) return;
  const double top = es.eigenvalues()(5);
  if (!(top > 0) || !std::isfinite(top)) return;
  Eigen::Matrix<double, 6, 1> y = Eigen::Matrix<double, 6, 1>::Zero();
  const Eigen::Matrix<double, 6, 1> gw = sw.asDiagonal() * g;
  for (int k = 0; k < 6; ++k) {
    const double lam = es.eigenvalues()(k);
    if (lam < kStrongDirection * top) continue;
    const Eigen::Matrix<double, 6, 1> u = es.eigenvectors().col(k);
    y -= u * (u.dot(gw) / lam);
  }
  const Vec6 xi = sw.asDiagonal() * y;
  if (!xi.allFinite()) return;
  r->photo_pull_m = xi.head<3>().norm();
  r->photo_pull_rad = xi.tail<3>().norm();
  const double pull = std::max(r->photo_pull_m / kPhotoPullM, r->photo_pull_rad / kPhotoPullRad);
  if (pull <= 1) return;
  // For small shares the pull falls about in proportion with the share: a share of 1/pull^2
  // leaves a pull of about 1/pull of the bound, less the farther the colour is off.
  const double share = 1.0 / (pull * pull) < kMinPhotoShare ? 0.0 : 1.0 / (pull * pull);
  // (A share of 0 keeps the photometric terms in the health sums: the verification goes on
  // judging the frame's radiance residual against the scan's usual one.)
  tracking::TrackerOptions t2 = topt;
  t2.photo_share = float(share);
  // The finest level again, from the pose found (its basin is reached).
  t2.levels = 1;
  t2.iterations[0] = topt.iterations[std::size_t(std::max(0, std::min(topt.levels, 4) - 1))];
  const tracking::GaussNewtonRun run = b.RunTracker(r->T_world_camera, t2, &prior);
  const double pull_m = r->photo_pull_m, pull_rad = r->photo_pull_rad;
  *r = tracking::JudgeTrack(run, start, std::min(b.LiveValid(), b.ReferenceValid()), topt, &prior);
  r->photo_share = share;
  r->photo_pull_m = pull_m, r->photo_pull_rad = pull_rad;
}

}  // namespace hdrf::pipeline
