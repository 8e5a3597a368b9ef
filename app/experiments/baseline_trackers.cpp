#include "baseline_trackers.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>
#include <optional>

#include "common/error.h"
#include "imaging/imaging.h"
#include "normalized_radiance/normalized_radiance.h"
#include "radiometry/radiance.h"
#include "radiometry/pcf.h"

namespace hdrf::experiments {

const char* BaselineName(BaselineKind k) {
  return k == BaselineKind::kNcc ? "ncc" : "joint-exposure";
}

namespace {

using Mat7 = Eigen::Matrix<double, 7, 7>;
using Vec7 = Eigen::Matrix<double, 7, 1>;

// The previous frame as a reference: world-frame vertices and normals, its image.
tracking::Reference ReferenceOf(const tracking::Live& live, const Pose& T, const PinholeCamera& cam, int levels) {
  const auto& L = live.levels[0];
  const RigidTransform R = ToRigidTransform(T);
  Image<Float3> vw(cam.width, cam.height), nw(cam.width, cam.height);
  for (std::size_t i = 0; i < vw.size(); ++i)
    if (L.vertex_c[i].z > 0) {
      vw[i] = R.Apply(L.vertex_c[i]);
      nw[i] = R.Rotate(L.normal_c[i]);
    }
  return tracking::MakeReference(vw, nw, L.intensity, cam, levels, T);
}

// Radiance pyramids that leave untrusted pixels (0) out: each coarser pixel is the mean of
// its trusted children (0 if none), and gradients are taken only between trusted pixels, so
// saturated or black regions do not bleed into the residuals at coarse levels.
void MaskedPyramid(tracking::Live& live) {
  for (std::size_t l = 0; l < live.levels.size(); ++l) {
    auto& L = live.levels[l];
    if (l > 0) {
      const auto& F = live.levels[l - 1].intensity;
      for (int y = 0; y < L.intensity.height(); ++y)
        for (int x = 0; x < L.intensity.width(); ++x) {
          float sum = 0.f;
          int n = 0;
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
              const float v = F(2 * x + dx, 2 * y + dy);
              if (v > 0.f) sum += v, ++n;
            }
          L.intensity(x, y) = n > 0 ? sum / float(n) : 0.f;
          if (n == 0) L.weight(x, y) = 0.f;
        }
    }
    const auto& I = L.intensity;
    for (int y = 0; y < I.height(); ++y)
      for (int x = 0; x < I.width(); ++x) {
        const bool okx = x > 0 && x + 1 < I.width() && I(x - 1, y) > 0.f && I(x + 1, y) > 0.f;
        const bool oky = y > 0 && y + 1 < I.height() && I(x, y - 1) > 0.f && I(x, y + 1) > 0.f;
        L.grad_x(x, y) = okx ? 0.5f * (I(x + 1, y) - I(x - 1, y)) : 0.f;
        L.grad_y(x, y) = oky ? 0.5f * (I(x, y + 1) - I(x, y - 1)) : 0.f;
        if (!(okx && oky)) L.weight(x, y) = 0.f;
      }
  }
}

// True when the four pixels around (u, v) are trusted.
bool Trusted(ImageView<const float> img, float u, float v) {
  const int ix = int(u), iy = int(v);
  return img(ix, iy) > 0.f && img(ix + 1, iy) > 0.f && img(ix, iy + 1) > 0.f && img(ix + 1, iy + 1) > 0.f;
}

// The live sample matched to reference pixel (x, y) at a pose: false where the reference has
// no vertex or value, or the warped point falls outside the live image or on untrusted pixels.
struct Match {
  float i_ref, il, wl;
  Float3 q;  // the reference point in the live camera frame
  Float2 u;  // its live pixel
};
bool MatchPixel(const tracking::ReferenceView& ref, const tracking::LiveView& live, const RigidTransform& T_live_world,
                int x, int y, Match* m) {
  const Float3 p = ref.vertex_w(x, y);
  m->i_ref = ref.intensity(x, y);
  if ((p.x == 0.f && p.y == 0.f && p.z == 0.f) || m->i_ref <= 0.f) return false;
  m->q = T_live_world.Apply(p);
  if (m->q.z <= 0.1f) return false;
  m->u = live.cam.Project(m->q);
  if (!imaging::SampleBilinear(live.intensity, m->u.x, m->u.y, &m->il) || !Trusted(live.intensity, m->u.x, m->u.y))
    return false;
  return imaging::SampleBilinear(live.weight, m->u.x, m->u.y, &m->wl) && m->wl > 0.f;
}

// Sums the 7-parameter normal equations of r = I_ref(x) - a I_live(w(x)) at one level.
struct JointSums {
  Mat7 H = Mat7::Zero();
  Vec7 g = Vec7::Zero();
  long n = 0;
};
JointSums AccumulateJoint(const tracking::ReferenceView& ref, const tracking::LiveView& live, const Pose& T_world_live,
                          double gain, const BaselineOptions& o) {
  const RigidTransform T_live_world = ToRigidTransform(T_world_live.inverse());
  JointSums total;
#pragma omp parallel
  {
    JointSums local;
#pragma omp for schedule(static) nowait
    for (int y = 0; y < ref.cam.height; ++y)
      for (int x = 0; x < ref.cam.width; ++x) {
        Match mt;
        if (!MatchPixel(ref, live, T_live_world, x, y, &mt)) continue;
        const PinholeCamera& c = live.cam;
        const Float3 q = mt.q;
        const Float2 u = mt.u;
        const float i_ref = mt.i_ref, il = mt.il, wl = mt.wl;
        float gx = 0.f, gy = 0.f;
        imaging::SampleBilinear(live.grad_x, u.x, u.y, &gx);
        imaging::SampleBilinear(live.grad_y, u.x, u.y, &gy);
        // Same geometry as tracking::PhotoTerm; the live image is scaled by the gain.
        const double iz = 1.0 / double(q.z);
        const double gu = gain * double(gx * c.fx) * iz, gv = gain * double(gy * c.fy) * iz;
        const double qx = q.x, qy = q.y, qz = q.z;
        const double dz = -(gu * qx + gv * qy) * iz;
        const double s = double(wl) / double(o.gain_sigma);
        Vec7 J;
        J << gu, gv, dz, qy * dz - qz * gv, qz * gu - qx * dz, qx * gv - qy * gu, -gain * double(il);
        J *= s;
        const double r = (double(i_ref) - gain * double(il)) * s;
        const double a = std::abs(r);
        const double w = a <= o.huber_k ? 1.0 : o.huber_k / a;
        local.H.selfadjointView<Eigen::Upper>().rankUpdate(J, w);
        local.g += w * r * J;
        ++local.n;
      }
#pragma omp critical
    {
      total.H += local.H;
      total.g += local.g;
      total.n += local.n;
    }
  }
  total.H = total.H.selfadjointView<Eigen::Upper>();
  return total;
}

// Starting gain: the median over matched pixels of I_ref / I_live at a pose (1 if too few).
double MedianRatio(const tracking::ReferenceView& ref, const tracking::LiveView& live, const Pose& T_world_live) {
  const RigidTransform T_live_world = ToRigidTransform(T_world_live.inverse());
  std::vector<double> r;
  for (int y = 0; y < ref.cam.height; ++y)
    for (int x = 0; x < ref.cam.width; ++x) {
      Match mt;
      if (MatchPixel(ref, live, T_live_world, x, y, &mt)) r.push_back(double(mt.i_ref) / double(mt.il));
    }
  if (r.size() < 50) return 1;
  std::nth_element(r.begin(), r.begin() + long(r.size() / 2), r.end());
  return r[r.size() / 2];
}

}  // namespace

struct BaselineTracker::State {
  BaselineKind kind;
  PinholeCamera cam;
  SensorInfo sensor;
  BaselineOptions o;
  std::optional<radiometry::PcfTables> pcf;
  std::optional<tracking::Reference> ref;
  Pose pose = Pose::Identity(), previous = Pose::Identity();
  float scale = 1, previous_scale = 1;  // joint exposure: the mean normalization of the frames
};

BaselineTracker::BaselineTracker(BaselineKind kind, const PinholeCamera& camera, const SensorInfo& sensor,
                                 const BaselineOptions& o)
    : s_(std::make_unique<State>()) {
  s_->kind = kind;
  s_->cam = camera;
  s_->sensor = sensor;
  s_->o = o;
  if (kind == BaselineKind::kJointExposure) {
    if (!sensor.response)
      throw Error("the joint-exposure tracker needs the sensor's response calibration (sensor.json 'response')");
    s_->pcf = radiometry::ComputePcf(*sensor.response,
                                     sensor.noise ? *sensor.noise : radiometry::DefaultNoise(*sensor.response));
  }
}

BaselineTracker::~BaselineTracker() = default;

BaselineStep BaselineTracker::Process(const ColorImage& color, const DepthImage& depth_m) {
  State& s = *s_;
  const int w = color.width(), h = color.height();
  if (w != s.cam.width || h != s.cam.height || depth_m.width() != w || depth_m.height() != h)
    throw Error("baseline tracker: frame size differs from the camera");
  const DepthImage depth = imaging::BilateralDepth(depth_m);
  Image<float> image, weight;
  if (s.kind == BaselineKind::kNcc) {
    Image<float> raw(w, h);
    for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = imaging::RawIntensityPixel(color[i]);
    image = nr::NormalizedRadiance(raw, {s.o.ncc_patch, 1, s.o.ncc_min_std});
    weight = Image<float>(w, h, 1.f);
  } else {
    RadianceImage rad;
    Image<float> maxconf;
    radiometry::ConvertFrame(color, *s.sensor.response, *s.pcf, s.o.pcf, rad, weight, maxconf);
    image = nr::Luminance(rad);
    // Scale to a mean of 1 over trusted pixels so the residual scale means the same in
    // every frame; the gain absorbs the rest. Untrusted pixels carry no reference value.
    double sum = 0;
    long n = 0;
    for (std::size_t i = 0; i < image.size(); ++i)
      if (weight[i] > 0) sum += image[i], ++n;
    const float k = n > 0 && sum > 0 ? float(double(n) / sum) : 1.f;
    for (std::size_t i = 0; i < image.size(); ++i) image[i] = weight[i] > 0 ? image[i] * k : 0.f;
    s.previous_scale = s.scale;
    s.scale = k;
  }
  tracking::Live live = tracking::MakeLive(depth, image, weight, s.cam, s.o.levels);
  if (s.kind == BaselineKind::kJointExposure) MaskedPyramid(live);
  BaselineStep step;
  if (!s.ref) {
    s.ref = ReferenceOf(live, s.pose, s.cam, s.o.levels);
    step.T_world_camera = s.pose;
    return step;
  }
  const Pose predicted = se3::Orthonormalized(s.pose * (s.previous.inverse() * s.pose));
  Pose T = predicted;
  const int levels = std::min(s.o.levels, int(live.levels.size()));
  if (s.kind == BaselineKind::kNcc) {
    tracking::TrackerOptions to;
    to.kind = tracking::TrackerKind::kNr;  // the photometric term, on the NCC image
    to.levels = levels;
    to.iterations = s.o.iterations;
    to.photo_sigma = s.o.ncc_sigma;
    to.huber_k = s.o.huber_k;
    const tracking::TrackResult r = tracking::Track(*s.ref, live, predicted, to);
    step.iterations = r.iterations;
    step.lost = r.iterations == 0;
    T = r.T_world_camera;
  } else {
    // Log gain of this pair, started from the median ratio at the prediction (coarsest level).
    double b = std::log(MedianRatio(s.ref->levels[std::size_t(levels - 1)].view(),
                                    live.levels[std::size_t(levels - 1)].view(), predicted));
    for (int l = levels - 1; l >= 0; --l) {
      const int iters = s.o.iterations[std::size_t(levels - 1 - l)];
      for (int it = 0; it < iters; ++it) {
        const JointSums js = AccumulateJoint(s.ref->levels[std::size_t(l)].view(), live.levels[std::size_t(l)].view(),
                                             T, std::exp(b), s.o);
        if (js.n < 12) break;
        const Mat7 Hd = js.H + 1e-6 * Mat7::Identity() * js.H.trace() / 7.0;
        const Vec7 d = Hd.ldlt().solve(-js.g);
        if (!d.allFinite()) break;
        T = se3::Orthonormalized(T * se3::Exp(Vec6(d.head<6>())));
        b += d(6);
        ++step.iterations;
        if (d.head<3>().norm() < 1e-5 && d.segment<3>(3).norm() < 1e-5 && std::abs(d(6)) < 1e-5) break;
      }
    }
    step.lost = step.iterations == 0;
    // k_ref L_ref = a k_live L_live, so L_ref / L_live = a k_live / k_ref.
    step.gain = std::exp(b) * double(s.scale) / double(s.previous_scale);
  }
  if (step.lost) T = predicted;
  s.previous = s.pose;
  s.pose = T;
  s.ref = ReferenceOf(live, T, s.cam, s.o.levels);
  step.T_world_camera = T;
  return step;
}

}  // namespace hdrf::experiments
