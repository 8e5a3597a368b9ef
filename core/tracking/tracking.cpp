#include "tracking/tracking.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "common/error.h"
#include "common/lanes.h"
#include "common/message.h"
#include "imaging/imaging.h"
#include "tracking/pyramid_driver.h"
#include "tracking/term_batch.h"

namespace hdrf::tracking {

TrackerKind ParseTrackerKind(const std::string& s) {
  if (s == "nr") return TrackerKind::kNr;
  if (s == "nr+icp") return TrackerKind::kNrIcp;
  if (s == "icp") return TrackerKind::kIcp;
  if (s == "intensity") return TrackerKind::kIntensity;
  throw SettingError("tracker.kind", "unknown tracker '" + s + "'; choose nr, nr+icp, icp or intensity");
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

int UsableLevels(int requested, int width, int height) {
  int levels = 1;
  while (levels < requested && (width >> levels) >= kMinCoarsestWidth && (height >> levels) >= kMinCoarsestHeight) ++levels;
  return levels;
}

void TrackerOptions::Check() const {
  if (levels < 1 || levels > 4) throw SettingError("tracker.levels", "must be 1 to 4");
  for (int i = 0; i < levels; ++i)
    if (iterations[std::size_t(i)] < 0) throw SettingError("tracker.iterations", "must be >= 0");
  // Coarse levels may be skipped; the finest may not: with no iteration there every pose is
  // the motion prediction, never measured against the frame.
  if (iterations[std::size_t(levels - 1)] < 1)
    throw SettingError("tracker.iterations", "the finest level (the last of " + std::to_string(levels) +
                                                 ") needs at least 1 iteration, or no pose is measured");
  if (!(icp_sigma_m > 0)) throw SettingError("tracker.icp_sigma_m", "must be > 0");
  if (!(photo_sigma > 0)) throw SettingError("tracker.photo_sigma", "must be > 0");
  if (!(huber_k > 0)) throw SettingError("tracker.huber_k", "must be > 0");
  if (!(icp_max_dist_m > 0)) throw SettingError("tracker.icp_max_dist_m", "must be > 0");
  if (!(icp_max_angle_deg > 0 && icp_max_angle_deg <= 90))
    throw SettingError("tracker.icp_max_angle_deg", "must be in (0, 90] degrees");
  if (!(min_inlier_share >= 0 && min_inlier_share <= 1))
    throw SettingError("tracker.min_inlier_share", "must be in [0, 1]");
  if (!(max_condition > 1)) throw SettingError("tracker.max_condition", "must be > 1");
  if (!(weak_info_floor >= 0 && weak_info_floor < 1)) throw SettingError("tracker.weak_info_floor", "must be in [0, 1)");
  if (!(max_jump_m > 0)) throw SettingError("tracker.max_jump_m", "must be > 0");
  if (!(max_speed_mps > 0)) throw SettingError("tracker.max_speed_mps", "must be > 0");
  if (!(max_jump_deg > 0 && max_jump_deg <= 180)) throw SettingError("tracker.max_jump_deg", "must be in (0, 180]");
  if (!(verify_growth >= 1 && verify_growth <= 1000)) throw SettingError("tracker.verify_growth", "must be in [1, 1000]");
  if (!(verify_floor_m >= 0 && verify_floor_m <= 1)) throw SettingError("tracker.verify_floor_m", "must be in [0, 1] m");
  if (!(verify_floor_photo >= 0 && verify_floor_photo <= 10))
    throw SettingError("tracker.verify_floor_photo", "must be in [0, 10]");
  if (!(min_robust_inliers >= 0 && min_robust_inliers <= 1))
    throw SettingError("tracker.min_robust_inliers", "must be in [0, 1]");
  if (!(max_exposure_drift > 0 && max_exposure_drift <= 100))
    throw SettingError("tracker.max_exposure_drift", "must be in (0, 100]");
  if (confirm_frames < 1 || confirm_frames > 1000) throw SettingError("tracker.confirm_frames", "must be 1 to 1000");
  if (!(min_anchor_depth >= 0 && min_anchor_depth <= 1)) throw SettingError("tracker.min_anchor_depth", "must be in [0, 1]");
  if (!(icp_depth_ref_m >= 0 && icp_depth_ref_m < 1e3)) throw SettingError("tracker.icp_depth_ref_m", "must be in [0, 1000) m");
  if (!(photo_share >= 0 && photo_share <= 1)) throw SettingError("tracker.photo_share", "must be in [0, 1]");
}

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6d = Eigen::Matrix<double, 6, 1>;

// Sums per-pixel terms over a w x h grid on the CPU threads: the rows are cut into fixed
// chunks of kChunkRows, each chunk summed on its own (by whichever thread is free: a thread
// slowed by other work, the studio's window among them, no longer holds the others at the
// end), and the chunks' sums are added in chunk order, so the result is the same on every
// run whatever the number of threads. Each chunk sums on the stack (sums side by side in
// one array shared cache lines: every pixel's update moved a line between the cores) and
// stores its sum once. With several terms (ICP and photometric, on one grid) each chunk
// sums each term on its own, in one parallel pass (a chunk's rows read once while in
// cache), and all of the first term's chunks are added before the second's: the same bits
// as summing the terms one after another.
template <typename... Terms>
void SumTerms(int w, int h, GnSystem& acc, const Terms&... terms) {
  constexpr int kChunkRows = 4, kTerms = int(sizeof...(Terms));
  const int chunks = (h + kChunkRows - 1) / kChunkRows;
  std::vector<GnSystem> partial(std::size_t(kTerms) * static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1)
  for (int c = 0; c < chunks; ++c) {
    const int y0 = c * kChunkRows, y1 = std::min(h, (c + 1) * kChunkRows);
    int k = 0;
    auto sum = [&](const auto& term) {
      GnSystem local;
      {
        TermBatch batch(local);
        for (int y = y0; y < y1; ++y) {
          if constexpr (requires { term.Row(y, w, batch); }) {
            term.Row(y, w, batch);
          } else {
            for (int x = 0; x < w; ++x) term(x, y, batch);
          }
        }
      }
      partial[std::size_t(k++) * std::size_t(chunks) + std::size_t(c)] = local;
    };
    (sum(terms), ...);
  }
  for (const GnSystem& p : partial) acc.Merge(p);
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
  a.z_ref_m = o.icp_depth_ref_m;
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
  a.share = o.photo_share;
  return a;
}

ReferenceView ReferenceLevel::view() const { return {cam, View(vertex_w), View(normal_w), View(intensity)}; }
LiveView LiveLevel::view() const {
  return {cam, View(vertex_c), View(normal_c), View(intensity), View(grad_x), View(grad_y), View(weight)};
}

namespace {

// IcpProject for pixels x .. x + 3 of row y, each lane with its operations in its order (the
// same bits); ok[k] as IcpProject's result.
void IcpProjectFour(const IcpArgs& a, int x, int y, Float3 p[4], int ux[4], int uy[4], bool ok[4]) {
  const Lanes3 v = Lanes3::Load(&a.live_vertex(x, y)), nl = Lanes3::Load(&a.live_normal(x, y));
  const LaneInts has = ~(v.z <= 0.f) & (nl.x * nl.x + nl.y * nl.y + nl.z * nl.z != 0.f);
  const Lanes3 pw = Apply(a.T_world_live, v), pr = Apply(a.T_ref_world, pw);
  const LaneInts front = has & ~(pr.z <= 0.f);
  const PinholeCamera& c = a.ref_cam;
  Lanes fu, fv;
  Project(c, pr, &fu, &fv);
  const LaneInts u = RoundToIntLanes(fu), w = RoundToIntLanes(fv);
  for (int k = 0; k < 4; ++k) {
    p[k] = pw[k];
    ux[k] = u[k], uy[k] = w[k];
    ok[k] = front[k] && !(u[k] < 0 || w[k] < 0 || u[k] >= c.width || w[k] >= c.height);
  }
}

// The ICP terms of a row: every pixel's projection first (IcpProject, four at once), then the
// terms at the reference pixels found (IcpAt), in pixel order: IcpTerm's operations and order.
struct IcpRows {
  IcpArgs a;
  void operator()(int x, int y, TermBatch& s) const { IcpTerm(a, x, y, s); }
  void Row(int y, int w, TermBatch& s) const {
    constexpr int kRun = 256;  // pixels a pass takes (a wider row: several runs, in order)
    Float3 p[kRun];
    int at[kRun];
    std::int32_t u[kRun][2];
    for (int x0 = 0; x0 < w; x0 += kRun) {
      int n = 0;
      const int end = std::min(w, x0 + kRun);
      int x = x0;
      for (; x + 4 <= end; x += 4) {
        Float3 p4[4];
        int ux[4], uy[4];
        bool ok[4];
        IcpProjectFour(a, x, y, p4, ux, uy, ok);
        for (int k = 0; k < 4; ++k)
          if (ok[k]) p[n] = p4[k], at[n] = x + k, u[n][0] = ux[k], u[n][1] = uy[k], ++n;
      }
      for (; x < end; ++x) {
        int ux, uy;
        if (IcpProject(a, x, y, &p[n], &ux, &uy)) at[n] = x, u[n][0] = ux, u[n][1] = uy, ++n;
      }
      for (int k = 0; k < n; ++k) IcpAt(a, at[k], y, p[k], u[k][0], u[k][1], s);
    }
  }
};

// PhotoProject for pixels x .. x + 3 of row y, each lane with its operations in its order
// (the same bits); ok[k] as PhotoProject's result.
void PhotoProjectFour(const PhotoArgs& a, int x, int y, Float3 q[4], imaging::BilinearAt at[4], float i_ref[4],
                      bool ok[4]) {
  const Lanes3 m = Lanes3::Load(&a.ref_vertex(x, y));
  const float* ir = &a.ref_intensity(x, y);
  const Lanes i = {ir[0], ir[1], ir[2], ir[3]};
  const LaneInts has = ~((m.x == 0.f) & (m.y == 0.f) & (m.z == 0.f)) & (i != 0.f);
  const Lanes3 qc = Apply(a.T_live_world, m);
  const LaneInts front = has & ~(qc.z <= 0.1f);
  Lanes ux, uy;
  Project(a.live_cam, qc, &ux, &uy);
  // BilinearAt::Set: inside [0, size - 1.001] along both axes, then the integer and fractional parts.
  const float xmax = float(a.live_intensity.width) - 1.001f, ymax = float(a.live_intensity.height) - 1.001f;
  const LaneInts inside = front & ~((ux < 0.f) | (uy < 0.f) | (ux > xmax) | (uy > ymax));
  const Lanes zero = {0.f, 0.f, 0.f, 0.f};
  const LaneInts ix = __builtin_convertvector(inside ? ux : zero, LaneInts), iy = __builtin_convertvector(inside ? uy : zero, LaneInts);
  const Lanes ax = ux - __builtin_convertvector(ix, Lanes), ay = uy - __builtin_convertvector(iy, Lanes);
  for (int k = 0; k < 4; ++k) {
    q[k] = qc[k];
    at[k].ix = ix[k], at[k].iy = iy[k], at[k].ax = ax[k], at[k].ay = ay[k];
    i_ref[k] = i[k];
    ok[k] = inside[k] != 0;
  }
}

// The photometric terms of a row: the projections first (four at once), then the terms, in
// pixel order: PhotoTerm's operations and order.
struct PhotoRows {
  PhotoArgs a;
  void operator()(int x, int y, TermBatch& s) const { PhotoTerm(a, x, y, s); }
  void Row(int y, int w, TermBatch& s) const {
    constexpr int kRun = 256;
    Float3 q[kRun];
    imaging::BilinearAt at[kRun];
    float i_ref[kRun];
    for (int x0 = 0; x0 < w; x0 += kRun) {
      int n = 0;
      const int end = std::min(w, x0 + kRun);
      int x = x0;
      for (; x + 4 <= end; x += 4) {
        Float3 q4[4];
        imaging::BilinearAt at4[4];
        float i4[4];
        bool ok[4];
        PhotoProjectFour(a, x, y, q4, at4, i4, ok);
        for (int k = 0; k < 4; ++k)
          if (ok[k]) q[n] = q4[k], at[n] = at4[k], i_ref[n] = i4[k], ++n;
      }
      for (; x < end; ++x)
        if (PhotoProject(a, x, y, &q[n], &at[n], &i_ref[n])) ++n;
      for (int k = 0; k < n; ++k) PhotoAt(a, q[k], at[k], i_ref[k], s);
    }
  }
};

}  // namespace

GnSystem AccumulateCpu(const ReferenceView& ref, const Pose& T_world_ref, const LiveView& live,
                       const Pose& T_world_live, const TrackerOptions& o) {
  GnSystem acc;
  const bool use_icp = o.kind == TrackerKind::kIcp || o.kind == TrackerKind::kNrIcp;
  const bool use_photo = o.kind != TrackerKind::kIcp;
  const IcpRows icp{use_icp ? MakeIcpArgs(ref, T_world_ref, live, T_world_live, o) : IcpArgs{}};
  const PhotoRows photo{use_photo ? MakePhotoArgs(ref, live, T_world_live, o) : PhotoArgs{}};
  if (use_icp && use_photo && live.cam.width == ref.cam.width && live.cam.height == ref.cam.height) {
    SumTerms(live.cam.width, live.cam.height, acc, icp, photo);
    return acc;
  }
  if (use_icp) SumTerms(live.cam.width, live.cam.height, acc, icp);
  if (use_photo) SumTerms(ref.cam.width, ref.cam.height, acc, photo);
  return acc;
}

Live MakeLive(const DepthImage& depth, const Image<float>& intensity, const Image<float>& weight,
              const PinholeCamera& cam, int levels, float max_normal_jump_m) {
  Live live;
  PinholeCamera c = cam;
  for (int l = 0; l < levels; ++l) {
    LiveLevel L;
    L.cam = c;
    L.depth = l == 0 ? depth.Clone() : DepthImage(c.width, c.height);
    L.intensity = l == 0 ? intensity.Clone() : Image<float>(c.width, c.height);
    L.weight = l == 0 ? weight.Clone() : Image<float>(c.width, c.height);
    L.grad_x = Image<float>(c.width, c.height);
    L.grad_y = Image<float>(c.width, c.height);
    L.vertex_c = Image<Float3>(c.width, c.height);
    L.normal_c = Image<Float3>(c.width, c.height);
    live.levels.push_back(std::move(L));
    c = c.Scaled(2);
  }
  std::vector<LiveLevelViews> views;
  for (LiveLevel& L : live.levels)
    views.push_back({L.cam, View(L.depth), View(L.intensity), View(L.weight), View(L.grad_x), View(L.grad_y),
                     View(L.vertex_c), View(L.normal_c)});
  for (std::size_t l = 0; l < views.size(); ++l)
    BuildLiveLevel(par::Host{}, l > 0 ? &views[l - 1] : nullptr, views[l], max_normal_jump_m);
  return live;
}

Reference MakeReference(const Image<Float3>& vertex_w, const Image<Float3>& normal_w,
                        const Image<float>& intensity, const PinholeCamera& cam, int levels,
                        const Pose& T_world_camera) {
  Reference ref;
  ref.T_world_camera = T_world_camera;
  ref.levels.push_back({cam, vertex_w.Clone(), normal_w.Clone(), intensity.Clone()});
  for (int l = 1; l < levels; ++l) {
    ReferenceLevel& p = ref.levels.back();
    const PinholeCamera c = p.cam.Scaled(2);
    ReferenceLevel L{c, Image<Float3>(c.width, c.height), Image<Float3>(c.width, c.height),
                     Image<float>(c.width, c.height)};
    BuildReferenceLevel(par::Host{}, {p.cam, View(p.vertex_w), View(p.normal_w), View(p.intensity)},
                        {L.cam, View(L.vertex_w), View(L.normal_w), View(L.intensity)});
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

PoseD ToPoseD(const Pose& T) {
  PoseD d;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) d.R[3 * i + j] = T.linear()(i, j);
    d.t[i] = T.translation()(i);
  }
  return d;
}

Pose FromPoseD(const PoseD& d) {
  Pose T = Pose::Identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) T.linear()(i, j) = d.R[3 * i + j];
    T.translation()(i) = d.t[i];
  }
  return T;
}

namespace {
constexpr double kMotionSigmaM = 0.01, kMotionSigmaRad = 1.0 * 3.14159265358979 / 180.0;
double PriorSpans(const MotionPrior* prior) { return prior && prior->frames > 0 ? prior->frames : 1.0; }
}  // namespace

StepPrior MakeStepPrior(const TrackerOptions& o, const MotionPrior* prior) {
  StepPrior p;
  if (!prior) return p;
  const double spans = PriorSpans(prior);
  p.on = true;
  p.T_predicted_inv = ToPoseD(prior->T_world_camera.inverse());
  p.sigma_m = kMotionSigmaM * spans;
  p.sigma_rad = kMotionSigmaRad * spans;
  // A prediction over several frame intervals (frames dropped) holds less: the floor falls
  // with the square of the intervals, as the prior's variance grows.
  p.floor = o.weak_info_floor / (spans * spans);
  return p;
}

GaussNewtonRun RunGaussNewton(const Accumulator& accumulate, int available_levels, const Pose& initial,
                              const TrackerOptions& o, const MotionPrior* prior) {
  const StepPrior sp = MakeStepPrior(o, prior);
  GaussNewtonRun run;
  PoseD T = ToPoseD(initial);
  const int levels = std::min(o.levels, available_levels);
  for (int l = levels - 1; l >= 0; --l) {
    const int iters = o.iterations[std::size_t(levels - 1 - l)];
    for (int it = 0; it < iters; ++it) {
      const GnSystem acc = accumulate(l, FromPoseD(T));
      const int out = GnStep(acc, sp, &T);
      if (out == kStepTooFew || out == kStepNotFinite) break;
      ++run.iterations;
      ++run.level_iterations[std::size_t(l)];
      if (l == 0) run.last = acc;
      if (out == kStepConverged) break;
    }
  }
  run.T_world_camera = FromPoseD(T);
  return run;
}

TrackResult Track(const Accumulator& accumulate, int available_levels, long live_valid, const Pose& initial,
                  const TrackerOptions& o, const MotionPrior* prior) {
  return JudgeTrack(RunGaussNewton(accumulate, available_levels, initial, o, prior), initial, live_valid, o, prior);
}

TrackResult JudgeTrack(const GaussNewtonRun& run, const Pose& initial, long live_valid, const TrackerOptions& o,
                       const MotionPrior* prior) {
  const double spans = PriorSpans(prior);
  const double sigma_m = kMotionSigmaM * spans, sigma_rad = kMotionSigmaRad * spans;
  TrackResult res;
  const Pose T = run.T_world_camera;
  GnSystem last = run.last;
  res.iterations = run.iterations;
  res.level_iterations = run.level_iterations;
  res.photo_share = o.kind == TrackerKind::kIcp ? 0.0 : double(o.photo_share);
  res.icp_depth_ref_m = o.icp_depth_ref_m;
  res.T_world_camera = T;
  res.rms_icp_m = last.icp_w() > 0 ? std::sqrt(last.icp_r2() / last.icp_w()) : 0;
  res.rms_photo = last.photo_w() > 0 ? std::sqrt(last.photo_r2() / last.photo_w()) : 0;
  if (prior) {
    const Vec6 e = se3::Log(prior->T_world_camera.inverse() * T);
    res.prior_offset_m = e.head<3>().norm();
    res.prior_offset_rad = e.tail<3>().norm();
    res.prior_sigmas = std::max(res.prior_offset_m / sigma_m, res.prior_offset_rad / sigma_rad);
  }
  res.icp_matched = last.icp_n();
  res.photo_matched = last.photo_n();
  res.icp_inliers = last.icp_n() > 0 ? last.icp_w() / last.icp_n() : 0;
  res.photo_inliers = last.photo_n() > 0 ? last.photo_w() / last.photo_n() : 0;
  // Health, at the finest level.
  const long matched = long(std::max(last.icp_n(), last.photo_n()));
  res.inlier_share = live_valid > 0 ? double(matched) / double(live_valid) : 0;
  Mat6 H_last;
  for (int i = 0, k = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j, ++k) H_last(i, j) = H_last(j, i) = last.v[k];
  Eigen::SelfAdjointEigenSolver<Mat6> es(H_last);
  const double lo = es.eigenvalues().minCoeff(), hi = es.eigenvalues().maxCoeff();
  res.condition = lo > 0 ? hi / lo : 1e30;
  {
    Vec6d sw;
    sw << kMotionSigmaM, kMotionSigmaM, kMotionSigmaM, kMotionSigmaRad, kMotionSigmaRad, kMotionSigmaRad;
    const Mat6 Hw = sw.asDiagonal() * H_last * sw.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Mat6> ew(Hw);
    res.weakest_info = ew.eigenvalues()(0);
    res.strongest_info = ew.eigenvalues()(5);
    if (prior) {
      const Vec6 e = se3::Log(prior->T_world_camera.inverse() * T);
      Vec6d ew6;
      for (int i = 0; i < 6; ++i) ew6(i) = e(i) / sw(i);
      res.weak_offset = ew.eigenvectors().col(0).dot(ew6);
    }
  }
  const Pose delta = initial.inverse() * T;
  if (res.iterations == 0 || matched < 50) {
    res.lost = true;
    res.why = Say(words::kNoCorrespondences);
  } else if (res.inlier_share < o.min_inlier_share) {
    res.lost = true;
    res.why = Say(words::kFewPixelsMatched, {std::to_string(int(100 * res.inlier_share))});
  } else if (res.condition > o.max_condition) {
    res.lost = true;
    res.why = Say(words::kIllConditioned);
  } else if (se3::TranslationNorm(delta) > o.max_jump_m ||
             se3::RotationAngle(delta) > o.max_jump_deg * 3.14159265 / 180.0) {
    res.lost = true;
    res.why = Say(words::kPoseJumped);
  }
  return res;
}

#if !HDRF_HAS_CUDA
void SetTrackerRunBlockLimit(int) {}
#endif

}  // namespace hdrf::tracking
