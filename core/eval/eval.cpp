#include "eval/eval.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace hdrf::eval {

TrajectoryError CompareTrajectories(const std::vector<Pose>& est, const std::vector<Pose>& gt) {
  if (est.size() != gt.size() || est.size() < 3)
    throw Error("trajectory comparison needs at least 3 associated poses, got " + std::to_string(std::min(est.size(), gt.size())));
  TrajectoryError e;
  e.pairs = est.size();
  // Horn / Umeyama without scale: gt ~ R est + t.
  Vec3 me = Vec3::Zero(), mg = Vec3::Zero();
  for (std::size_t i = 0; i < est.size(); ++i) {
    me += est[i].translation();
    mg += gt[i].translation();
  }
  me /= double(est.size());
  mg /= double(gt.size());
  Mat3 C = Mat3::Zero();
  for (std::size_t i = 0; i < est.size(); ++i)
    C += (gt[i].translation() - mg) * (est[i].translation() - me).transpose();
  Eigen::JacobiSVD<Mat3> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 S = Mat3::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) S(2, 2) = -1;
  const Mat3 R = svd.matrixU() * S * svd.matrixV().transpose();
  e.T_gt_est.linear() = R;
  e.T_gt_est.translation() = mg - R * me;
  std::vector<double> d;
  double s2 = 0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const double err = (e.T_gt_est * est[i].translation() - gt[i].translation()).norm();
    d.push_back(err);
    s2 += err * err;
  }
  e.ate_rmse_m = std::sqrt(s2 / double(d.size()));
  e.ate_max_m = *std::max_element(d.begin(), d.end());
  std::nth_element(d.begin(), d.begin() + long(d.size() / 2), d.end());
  e.ate_median_m = d[d.size() / 2];
  double t2 = 0, r2 = 0;
  for (std::size_t i = 1; i < est.size(); ++i) {
    const Pose de = est[i - 1].inverse() * est[i];
    const Pose dg = gt[i - 1].inverse() * gt[i];
    const Pose err = dg.inverse() * de;
    t2 += err.translation().squaredNorm();
    const double a = se3::RotationAngle(err) * 180.0 / M_PI;
    r2 += a * a;
  }
  e.rpe_trans_rmse_m = std::sqrt(t2 / double(est.size() - 1));
  e.rpe_rot_rmse_deg = std::sqrt(r2 / double(est.size() - 1));
  return e;
}

}  // namespace hdrf::eval
