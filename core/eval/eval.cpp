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

namespace {
double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}
}  // namespace

double RangeStops(std::vector<double> v, double lo, double hi) {
  if (v.size() < 2) return 0;
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) { return v[std::size_t(std::lround(q * double(v.size() - 1)))]; };
  const double a = at(lo), b = at(hi);
  return a > 0 && b > 0 ? std::log2(b / a) : 0;
}

namespace {
float Channel(const Float3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }
}  // namespace

ModelError CompareModel(const mesh::Mesh& m, const sim::Scene& scene, const Pose& T_scene_model,
                        std::size_t max_samples) {
  ModelError e;
  e.vertices = m.position.size();
  const RigidTransform T = ToRigidTransform(T_scene_model);
  std::vector<double> dist;
  std::vector<Float3> est, truth;
  const std::size_t step = std::max<std::size_t>(1, m.position.size() / std::max<std::size_t>(1, max_samples));
  for (std::size_t i = 0; i < m.position.size(); i += step) {
    const Float3 p = T.Apply(m.position[i]);
    dist.push_back(scene.DistanceToSurface(p));
    if (MaxComponent(m.radiance[i]) > 0) {
      est.push_back(m.radiance[i]);
      truth.push_back(scene.RadianceAt(p));
    }
  }
  e.mesh_median_distance_m = Median(dist);
  e.radiance_samples = est.size();
  if (est.empty()) return e;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> r;
    for (std::size_t i = 0; i < est.size(); ++i) {
      const double a = Channel(est[i], c), b = Channel(truth[i], c);
      if (a > 0 && b > 0) r.push_back(std::log(b / a));
    }
    e.scale[c] = std::exp(Median(r));
  }
  std::vector<double> lum_est, lum_true;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Float3 a{float(est[i].x * e.scale[0]), float(est[i].y * e.scale[1]), float(est[i].z * e.scale[2])};
    if (Luminance(a) > 0 && Luminance(truth[i]) > 0) {
      lum_est.push_back(Luminance(a));
      lum_true.push_back(Luminance(truth[i]));
    }
  }
  e.model_range_stops = RangeStops(lum_est);
  e.true_range_stops = RangeStops(lum_true);
  std::vector<double> stops;
  for (std::size_t i = 0; i < est.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double a = Channel(est[i], c) * e.scale[c], b = Channel(truth[i], c);
      if (a > 0 && b > 0) stops.push_back(std::abs(std::log2(a / b)));
    }
  if (stops.empty()) return e;
  const auto share = [&](double lim) {
    return double(std::count_if(stops.begin(), stops.end(), [lim](double s) { return s <= lim; })) /
           double(stops.size());
  };
  e.radiance_median_stops = Median(stops);
  e.within_01_stop = share(0.1);
  e.within_025_stop = share(0.25);
  return e;
}

}  // namespace hdrf::eval
