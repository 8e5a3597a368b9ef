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
  Image<float> g(im.width(), im.height());
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) g(x, y) = imaging::GradXPixel(View(im), x, y);
  return g;
}
Image<float> GradY(const Image<float>& im) {
  Image<float> g(im.width(), im.height());
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) g(x, y) = imaging::GradYPixel(View(im), x, y);
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

// Sums a per-pixel term over a w x h grid on the CPU threads.
template <typename Term>
void SumTerms(int w, int h, const Term& term, GnSystem& acc) {
#pragma omp parallel
  {
    GnSystem local;
#pragma omp for schedule(static) nowait
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) term(x, y, local);
#pragma omp critical
    acc.Merge(local);
  }
}

}  // namespace

IcpArgs MakeIcpArgs(const ReferenceView& ref, const Pose& T_world_ref, const LiveView& live,
                    const Pose& T_world_live, const TrackerOptions& o) {
  IcpArgs a{};
  a.live_vertex = live.vertex_c;
  a.live_normal = live.normal_c;
  a.ref_vertex = ref.vertex_w;
  a.ref_normal = ref.normal_w;
  a.ref_cam = ref.cam;
  a.T_world_live = ToRigidTransform(T_world_live);
  a.T_ref_world = ToRigidTransform(T_world_ref.inverse());
  const Eigen::Matrix3d R = T_world_live.rotation();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a.R_world_live[3 * i + j] = R(i, j);
  a.cos_max_angle = std::cos(o.icp_max_angle_deg * 3.14159265f / 180.f);
  a.max_dist = o.icp_max_dist_m;
  a.inv_sigma = 1.f / o.icp_sigma_m;
  a.huber_k = o.huber_k;
  return a;
}

PhotoArgs MakePhotoArgs(const ReferenceView& ref, const LiveView& live, const Pose& T_world_live,
                        const TrackerOptions& o) {
  PhotoArgs a{};
  a.ref_vertex = ref.vertex_w;
  a.ref_intensity = ref.intensity;
  a.live_intensity = live.intensity;
  a.live_weight = live.weight;
  a.live_gx = live.grad_x;
  a.live_gy = live.grad_y;
  a.live_cam = live.cam;
  a.T_live_world = ToRigidTransform(T_world_live.inverse());
  a.photo_sigma = o.photo_sigma;
  a.huber_k = o.huber_k;
  return a;
}

ReferenceView ReferenceLevel::view() const { return {cam, View(vertex_w), View(normal_w), View(intensity)}; }
LiveView LiveLevel::view() const {
  return {cam, View(vertex_c), View(normal_c), View(intensity), View(grad_x), View(grad_y), View(weight)};
}

GnSystem AccumulateCpu(const ReferenceView& ref, const Pose& T_world_ref, const LiveView& live,
                       const Pose& T_world_live, const TrackerOptions& o) {
  GnSystem acc;
  const bool use_icp = o.kind == TrackerKind::kIcp || o.kind == TrackerKind::kNrIcp;
  const bool use_photo = o.kind != TrackerKind::kIcp;
  if (use_icp) {
    const IcpArgs a = MakeIcpArgs(ref, T_world_ref, live, T_world_live, o);
    SumTerms(live.cam.width, live.cam.height, [&](int x, int y, GnSystem& s) { IcpTerm(a, x, y, s); }, acc);
  }
  if (use_photo) {
    const PhotoArgs a = MakePhotoArgs(ref, live, T_world_live, o);
    SumTerms(ref.cam.width, ref.cam.height, [&](int x, int y, GnSystem& s) { PhotoTerm(a, x, y, s); }, acc);
  }
  return acc;
}

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
  const int levels = int(std::min(ref.levels.size(), live.levels.size()));
  long live_valid = 0;
  const LiveLevel& L0 = live.levels[0];
  for (std::size_t i = 0; i < L0.vertex_c.size(); ++i) live_valid += L0.vertex_c[i].z > 0;
  return Track(
      [&](int l, const Pose& T) {
        return AccumulateCpu(ref.levels[std::size_t(l)].view(), ref.T_world_camera,
                             live.levels[std::size_t(l)].view(), T, o);
      },
      levels, live_valid, initial, o);
}

TrackResult Track(const Accumulator& accumulate, int available_levels, long live_valid,
                  const Pose& initial, const TrackerOptions& o) {
  TrackResult res;
  Pose T = initial;
  const int levels = std::min(o.levels, available_levels);
  GnSystem last;
  for (int l = levels - 1; l >= 0; --l) {
    const int iters = o.iterations[std::size_t(levels - 1 - l)];
    for (int it = 0; it < iters; ++it) {
      GnSystem acc = accumulate(l, T);
      if (acc.icp_n() + acc.photo_n() < 12) break;
      Mat6 H;
      Vec6d g;
      for (int i = 0, k = 0; i < 6; ++i) {
        for (int j = i; j < 6; ++j, ++k) H(i, j) = H(j, i) = acc.v[k];
        g(i) = acc.v[GnSystem::kH + i];
      }
      const Mat6 Hd = H + 1e-6 * Mat6::Identity() * H.trace() / 6.0;
      const Vec6d xi = Hd.ldlt().solve(-g);
      if (!xi.allFinite()) break;
      T = se3::Orthonormalized(T * se3::Exp(Vec6(xi)));
      ++res.iterations;
      if (l == 0) last = acc;
      if (xi.head<3>().norm() < 1e-5 && xi.tail<3>().norm() < 1e-5) break;
    }
  }
  res.T_world_camera = T;
  res.rms_icp_m = last.icp_w() > 0 ? std::sqrt(last.icp_r2() / last.icp_w()) : 0;
  res.rms_photo = last.photo_w() > 0 ? std::sqrt(last.photo_r2() / last.photo_w()) : 0;
  // Health, at the finest level.
  const long matched = long(std::max(last.icp_n(), last.photo_n()));
  res.inlier_share = live_valid > 0 ? double(matched) / double(live_valid) : 0;
  Mat6 H_last;
  for (int i = 0, k = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j, ++k) H_last(i, j) = H_last(j, i) = last.v[k];
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
  const ExposureArgs a{View(model_vertex_w), View(model_radiance), View(live_radiance),
                       View(live_conf), cam, ToRigidTransform(T_world_live.inverse())};
  std::vector<std::pair<float, float>> samples;  // (log ratio, weight)
  for (int y = 0; y < model_vertex_w.height(); y += 2)
    for (int x = 0; x < model_vertex_w.width(); x += 2) {
      float lr, w;
      if (ExposureSample(a, x, y, &lr, &w)) samples.emplace_back(lr, w);
    }
  return WeightedMedianRatio(samples);
}

ExposureEstimate WeightedMedianRatio(std::vector<std::pair<float, float>>& samples) {
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
