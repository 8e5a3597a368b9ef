#include "eval/eval.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <unordered_map>

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

namespace {
// Squared distance from p to triangle abc (closest point by region, after Ericson).
double PointTriangleDistance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).squaredNorm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).squaredNorm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).squaredNorm();
}
}  // namespace

Completeness SurfaceCompleteness(const mesh::Mesh& m, const std::vector<Float3>& points, double tol) {
  if (!(tol > 0)) throw Error("completeness needs a positive tolerance");
  // Triangles binned into cells of side `tol` by their bounding boxes; a point looks at the
  // 27 cells around its own.
  auto cell = [tol](double v) { return std::int64_t(std::floor(v / tol)); };
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (std::uint64_t(x & 0x1fffff) << 42) | (std::uint64_t(y & 0x1fffff) << 21) | std::uint64_t(z & 0x1fffff);
  };
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> grid;
  auto V = [&](std::int32_t i) { const Float3& f = m.position[std::size_t(i)]; return Vec3(f.x, f.y, f.z); };
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tr = m.triangles[t];
    Vec3 lo = V(tr[0]).cwiseMin(V(tr[1])).cwiseMin(V(tr[2])), hi = V(tr[0]).cwiseMax(V(tr[1])).cwiseMax(V(tr[2]));
    for (std::int64_t z = cell(lo.z()); z <= cell(hi.z()); ++z)
      for (std::int64_t y = cell(lo.y()); y <= cell(hi.y()); ++y)
        for (std::int64_t x = cell(lo.x()); x <= cell(hi.x()); ++x) grid[key(x, y, z)].push_back(std::int32_t(t));
  }
  Completeness c;
  c.points = points.size();
  const double tol2 = tol * tol;
  long within = 0;
#pragma omp parallel for schedule(dynamic, 1024) reduction(+ : within)
  for (long i = 0; i < long(points.size()); ++i) {
    const Vec3 p(points[std::size_t(i)].x, points[std::size_t(i)].y, points[std::size_t(i)].z);
    const std::int64_t cx = cell(p.x()), cy = cell(p.y()), cz = cell(p.z());
    bool hit = false;
    for (int dz = -1; dz <= 1 && !hit; ++dz)
      for (int dy = -1; dy <= 1 && !hit; ++dy)
        for (int dx = -1; dx <= 1 && !hit; ++dx) {
          const auto it = grid.find(key(cx + dx, cy + dy, cz + dz));
          if (it == grid.end()) continue;
          for (const std::int32_t t : it->second) {
            const auto& tr = m.triangles[std::size_t(t)];
            if (PointTriangleDistance2(p, V(tr[0]), V(tr[1]), V(tr[2])) <= tol2) {
              hit = true;
              break;
            }
          }
        }
    within += hit;
  }
  c.within = std::size_t(within);
  return c;
}

}  // namespace hdrf::eval
