#include "tracking/tracking.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "imaging/imaging.h"

namespace hdrf::tracking {

TrackerKind ParseTrackerKind(const std::string& s) {
  if (s == "nr") return TrackerKind::kNr;
  if (s == "nr+icp") return TrackerKind::kNrIcp;
  if (s == "icp") return TrackerKind::kIcp;
  if (s == "intensity") return TrackerKind::kIntensity;
  throw SettingError("--tracker", "unknown tracker '" + s + "'; choose nr, nr+icp, icp or intensity");
}

const char* TrackerName(TrackerKind k) {
  switch (k) {
    case TrackerKind::kNr: return "nr";
    case TrackerKind::kNrIcp: return "nr+icp";
    case TrackerKind::kIcp: return "icp";
    case TrackerKind::kIntensity: return "intensity";
  }
  return "?";
}

void TrackerOptions::Check() const {
  if (levels < 1 || levels > 4) throw SettingError("tracker.levels", "must be 1 to 4");
  for (int i = 0; i < levels; ++i)
    if (iterations[std::size_t(i)] < 0) throw SettingError("tracker.iterations", "must be >= 0");
  if (!(icp_sigma_m > 0) || !(photo_sigma > 0) || !(huber_k > 0))
    throw SettingError("tracker.sigma", "residual scales and the Huber threshold must be > 0");
}

namespace {

Image<float> GradX(const Image<float>& im) {
  Image<float> g(im.width(), im.height(), 0.f);
  for (int y = 0; y < im.height(); ++y)
    for (int x = 1; x + 1 < im.width(); ++x) g(x, y) = 0.5f * (im(x + 1, y) - im(x - 1, y));
  return g;
}
Image<float> GradY(const Image<float>& im) {
  Image<float> g(im.width(), im.height(), 0.f);
  for (int y = 1; y + 1 < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) g(x, y) = 0.5f * (im(x, y + 1) - im(x, y - 1));
  return g;
}
template <typename T>
Image<T> Subsample(const Image<T>& im) {
  Image<T> out(im.width() / 2, im.height() / 2);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) out(x, y) = im(2 * x, 2 * y);
  return out;
}

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6d = Eigen::Matrix<double, 6, 1>;

struct Accum {
  Mat6 H = Mat6::Zero();
  Vec6d g = Vec6d::Zero();
  double icp_r2 = 0, photo_r2 = 0, icp_w = 0, photo_w = 0;
  long icp_n = 0, photo_n = 0;
  void Add(const Vec6d& J, double r, double w) {
    H.noalias() += w * J * J.transpose();
    g.noalias() += w * r * J;
  }
  void Merge(const Accum& o) {
    H += o.H;
    g += o.g;
    icp_r2 += o.icp_r2;
    photo_r2 += o.photo_r2;
    icp_w += o.icp_w;
    photo_w += o.photo_w;
    icp_n += o.icp_n;
    photo_n += o.photo_n;
  }
};

double Huber(double r_scaled, double k) {
  const double a = std::abs(r_scaled);
  return a <= k ? 1.0 : k / a;
}

// Point-to-plane terms: live vertices (camera) against reference vertices/normals (world),
// associated by projecting into the reference camera.
void AddIcp(const ReferenceLevel& ref, const Pose& T_world_ref, const LiveLevel& live,
            const Pose& T_world_live, const TrackerOptions& o, Accum& acc) {
  const RigidTransform Tl = ToRigidTransform(T_world_live);
  const RigidTransform Tr_inv = ToRigidTransform(T_world_ref.inverse());
  const Eigen::Matrix3d R = T_world_live.rotation();
  const float cos_max = std::cos(o.icp_max_angle_deg * 3.14159265f / 180.f);
  const int w = live.cam.width, h = live.cam.height;
#pragma omp parallel
  {
    Accum local;
#pragma omp for schedule(static) nowait
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Float3 v = live.vertex_c(x, y);
        const Float3 nl = live.normal_c(x, y);
        if (v.z <= 0 || Length(nl) == 0) continue;
        const Float3 p = Tl.Apply(v);
        const Float3 pr = Tr_inv.Apply(p);
        if (pr.z <= 0) continue;
        const Float2 u = ref.cam.Project(pr);
        const int ux = int(std::lround(u.x)), uy = int(std::lround(u.y));
        if (ux < 0 || uy < 0 || ux >= ref.cam.width || uy >= ref.cam.height) continue;
        const Float3 m = ref.vertex_w(ux, uy), n = ref.normal_w(ux, uy);
        if (Length(n) == 0) continue;
        const Float3 d = p - m;
        if (Length(d) > o.icp_max_dist_m) continue;
        if (Dot(n, Tl.Rotate(nl)) < cos_max) continue;
        const double r = Dot(n, d);
        const Eigen::Vector3d nw(n.x, n.y, n.z);
        const Eigen::Vector3d a = R.transpose() * nw;
        const Eigen::Vector3d vv(v.x, v.y, v.z);
        Vec6d J;
        J.head<3>() = a;
        J.tail<3>() = vv.cross(a);
        const double s = 1.0 / o.icp_sigma_m;
        const double wgt = Huber(r * s, o.huber_k);
        local.Add(J * s, r * s, wgt);
        local.icp_r2 += wgt * r * r;
        local.icp_w += wgt;
        ++local.icp_n;
      }
#pragma omp critical
    acc.Merge(local);
  }
}

// Photometric terms: reference pixels (world vertex, NR) warped into the live frame,
// residual NR_ref - NR_live(u'), weighted by the live PCF.
void AddPhoto(const ReferenceLevel& ref, const LiveLevel& live, const Pose& T_world_live,
              const TrackerOptions& o, Accum& acc) {
  const RigidTransform Tl_inv = ToRigidTransform(T_world_live.inverse());
  const int w = ref.cam.width, h = ref.cam.height;
  const PinholeCamera& c = live.cam;
#pragma omp parallel
  {
    Accum local;
#pragma omp for schedule(static) nowait
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Float3 m = ref.vertex_w(x, y);
        if (m.x == 0 && m.y == 0 && m.z == 0) continue;
        const float i_ref = ref.intensity(x, y);
        if (i_ref == 0) continue;  // no model radiance here
        const Float3 q = Tl_inv.Apply(m);
        if (q.z <= 0.1f) continue;
        const Float2 u = c.Project(q);
        float il, gx, gy, wl;
        if (!imaging::SampleBilinear(live.intensity, u.x, u.y, &il)) continue;
        if (!imaging::SampleBilinear(live.weight, u.x, u.y, &wl) || wl <= 0) continue;
        imaging::SampleBilinear(live.grad_x, u.x, u.y, &gx);
        imaging::SampleBilinear(live.grad_y, u.x, u.y, &gy);
        const double r = double(i_ref) - il;
        const double iz = 1.0 / q.z;
        // d(pi)/dq times dq/dxi, with dq/dxi = [-I, [q]x] for T_live <- T_live exp(xi).
        const double gu = gx * c.fx * iz, gv = gy * c.fy * iz;
        const Eigen::Vector3d dI_dq(gu, gv, -(gu * q.x + gv * q.y) * iz);
        const Eigen::Vector3d qq(q.x, q.y, q.z);
        Vec6d J;
        J.head<3>() = dI_dq;               // d r / d xi_v = -dI/dq * (-I)
        J.tail<3>() = qq.cross(dI_dq);     // d r / d xi_w = -dI/dq [q]x, i.e. q x dI/dq
        const double s = wl / o.photo_sigma;
        const double wgt = Huber(r * s, o.huber_k);
        local.Add(J * s, r * s, wgt);
        local.photo_r2 += wgt * r * r;
        local.photo_w += wgt;
        ++local.photo_n;
      }
#pragma omp critical
    acc.Merge(local);
  }
}

}  // namespace

Live MakeLive(const DepthImage& depth, const Image<float>& intensity, const Image<float>& weight,
              const PinholeCamera& cam, int levels) {
  Live live;
  DepthImage d = depth.Clone();
  Image<float> in = intensity.Clone(), wt = weight.Clone();
  PinholeCamera c = cam;
  for (int l = 0; l < levels; ++l) {
    LiveLevel L;
    L.cam = c;
    L.vertex_c = imaging::VertexMap(d, c);
    L.normal_c = imaging::NormalMap(L.vertex_c);
    L.grad_x = GradX(in);
    L.grad_y = GradY(in);
    L.intensity = in.Clone();
    L.weight = wt.Clone();
    live.levels.push_back(std::move(L));
    if (l + 1 < levels) {
      d = imaging::DownsampleDepth(d);
      in = imaging::Downsample(in);
      wt = imaging::Downsample(wt);
      c = c.Scaled(2);
    }
  }
  return live;
}

Reference MakeReference(const Image<Float3>& vertex_w, const Image<Float3>& normal_w,
                        const Image<float>& intensity, const PinholeCamera& cam, int levels,
                        const Pose& T_world_camera) {
  Reference ref;
  ref.T_world_camera = T_world_camera;
  ReferenceLevel L0{cam, vertex_w.Clone(), normal_w.Clone(), intensity.Clone()};
  ref.levels.push_back(std::move(L0));
  for (int l = 1; l < levels; ++l) {
    const ReferenceLevel& p = ref.levels.back();
    ReferenceLevel L{p.cam.Scaled(2), Subsample(p.vertex_w), Subsample(p.normal_w),
                     imaging::Downsample(p.intensity)};
    ref.levels.push_back(std::move(L));
  }
  return ref;
}

TrackResult Track(const Reference& ref, const Live& live, const Pose& initial,
                  const TrackerOptions& o) {
  TrackResult res;
  Pose T = initial;
  const bool use_icp = o.kind == TrackerKind::kIcp || o.kind == TrackerKind::kNrIcp;
  const bool use_photo = o.kind != TrackerKind::kIcp;
  const int levels = std::min<int>(o.levels, int(std::min(ref.levels.size(), live.levels.size())));
  Mat6 H_last = Mat6::Zero();
  Accum last;
  for (int l = levels - 1; l >= 0; --l) {
    const int iters = o.iterations[std::size_t(levels - 1 - l)];
    for (int it = 0; it < iters; ++it) {
      Accum acc;
      if (use_icp) AddIcp(ref.levels[std::size_t(l)], ref.T_world_camera, live.levels[std::size_t(l)], T, o, acc);
      if (use_photo) AddPhoto(ref.levels[std::size_t(l)], live.levels[std::size_t(l)], T, o, acc);
      if (acc.icp_n + acc.photo_n < 12) break;
      const Mat6 Hd = acc.H + 1e-6 * Mat6::Identity() * acc.H.trace() / 6.0;
      const Vec6d xi = Hd.ldlt().solve(-acc.g);
      if (!xi.allFinite()) break;
      T = se3::Orthonormalized(T * se3::Exp(Vec6(xi)));
      ++res.iterations;
      if (l == 0) {
        H_last = acc.H;
        last = acc;
      }
      if (xi.head<3>().norm() < 1e-5 && xi.tail<3>().norm() < 1e-5) break;
    }
  }
  res.T_world_camera = T;
  res.rms_icp_m = last.icp_w > 0 ? std::sqrt(last.icp_r2 / last.icp_w) : 0;
  res.rms_photo = last.photo_w > 0 ? std::sqrt(last.photo_r2 / last.photo_w) : 0;
  // Health, at the finest level.
  long live_valid = 0;
  const LiveLevel& L0 = live.levels[0];
  for (std::size_t i = 0; i < L0.vertex_c.size(); ++i) live_valid += L0.vertex_c[i].z > 0;
  const long matched = std::max(last.icp_n, last.photo_n);
  res.inlier_share = live_valid > 0 ? double(matched) / double(live_valid) : 0;
  Eigen::SelfAdjointEigenSolver<Mat6> es(H_last);
  const double lo = es.eigenvalues().minCoeff(), hi = es.eigenvalues().maxCoeff();
  res.condition = lo > 0 ? hi / lo : 1e30;
  const Pose delta = initial.inverse() * T;
  if (res.iterations == 0 || matched < 50) {
    res.lost = true;
    res.why = "no correspondences";
  } else if (res.inlier_share < o.min_inlier_share) {
    res.lost = true;
    res.why = "only " + std::to_string(int(100 * res.inlier_share)) + " % of pixels matched";
  } else if (res.condition > o.max_condition) {
    res.lost = true;
    res.why = "ill-conditioned (geometry and texture too poor)";
  } else if (se3::TranslationNorm(delta) > o.max_jump_m ||
             se3::RotationAngle(delta) > o.max_jump_deg * 3.14159265 / 180.0) {
    res.lost = true;
    res.why = "pose jumped implausibly far";
  }
  return res;
}

ExposureEstimate EstimateExposureRatio(const Image<Float3>& model_vertex_w,
                                       const RadianceImage& model_radiance,
                                       const RadianceImage& live_radiance,
                                       const Image<float>& live_conf, const PinholeCamera& cam,
                                       const Pose& T_world_live) {
  const RigidTransform Tinv = ToRigidTransform(T_world_live.inverse());
  std::vector<std::pair<float, float>> samples;  // (log ratio, weight)
  for (int y = 0; y < model_vertex_w.height(); y += 2)
    for (int x = 0; x < model_vertex_w.width(); x += 2) {
      const Float3 m = model_vertex_w(x, y);
      const float lm = hdrf::Luminance(model_radiance(x, y));
      if (!(lm > 0) || (m.x == 0 && m.y == 0 && m.z == 0)) continue;
      const Float3 q = Tinv.Apply(m);
      if (q.z <= 0.1f) continue;
      const Float2 u = cam.Project(q);
      const int ux = int(std::lround(u.x)), uy = int(std::lround(u.y));
      if (ux < 0 || uy < 0 || ux >= cam.width || uy >= cam.height) continue;
      const float wl = live_conf(ux, uy);
      const float ll = hdrf::Luminance(live_radiance(ux, uy));
      if (wl <= 0 || !(ll > 0)) continue;
      samples.emplace_back(std::log(lm / ll), wl);
    }
  ExposureEstimate e;
  e.samples = long(samples.size());
  if (samples.size() < 50) return e;
  std::sort(samples.begin(), samples.end());
  double total = 0;
  for (auto& s : samples) total += s.second;
  double acc = 0;
  for (auto& s : samples) {
    acc += s.second;
    if (acc >= 0.5 * total) {
      e.ratio = std::exp(double(s.first));
      break;
    }
  }
  e.valid = true;
  return e;
}

}  // namespace hdrf::tracking
