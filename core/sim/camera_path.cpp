#include "sim/camera_path.h"

#include <cmath>

#include "common/error.h"
#include "sim/noise.h"

namespace hdrf::sim {

namespace {
Vec3 V(Float3 f) { return {f.x, f.y, f.z}; }
double Ease(double t) { return t * t * (3.0 - 2.0 * t); }
}  // namespace

Pose LookAt(const Vec3& eye, const Vec3& target, double roll) {
  Vec3 f = (target - eye).normalized();
  // A hand-held camera rarely looks straight up or down, and the camera's roll is undefined
  // there: keep the pitch within +-55 degrees so the frame turns smoothly.
  constexpr double kMaxSin = 0.82;
  if (std::abs(f.z()) > kMaxSin) {
    Vec3 h(f.x(), f.y(), 0);
    if (h.norm() < 1e-6) h = Vec3(1, 0, 0);
    h.normalize();
    f = (h * std::sqrt(1 - kMaxSin * kMaxSin) + Vec3(0, 0, f.z() > 0 ? kMaxSin : -kMaxSin)).normalized();
  }
  const Vec3 up(0, 0, 1);
  const Vec3 r = f.cross(up).normalized();
  const Vec3 d = f.cross(r);
  Mat3 R;
  R.col(0) = r;
  R.col(1) = d;
  R.col(2) = f;
  Pose T = Pose::Identity();
  T.linear() = R * Eigen::AngleAxisd(roll, Vec3::UnitZ()).toRotationMatrix();
  T.translation() = eye;
  return T;
}

CameraPath CameraPath::Handheld(const Scene& scene, std::uint32_t seed, int frames, double fps,
                                double segment_s) {
  if (frames <= 0) throw SettingError("--frames", "must be positive");
  CameraPath path;
  path.fps_ = fps;
  // Targets alternate bright, dark, bright, ... in a seeded order.
  std::vector<Vec3> targets;
  const auto& bright = scene.bright_targets();
  const auto& dark = scene.dark_targets();
  const std::size_t n = std::max(bright.size(), dark.size());
  for (std::size_t k = 0; k < 2 * n; ++k) {
    const auto& list = (k % 2 == 0) ? bright : dark;
    targets.push_back(V(list[(k / 2 + Hash32(seed) % list.size()) % list.size()]));
  }
  const Vec3 lo = V(scene.room_lo()), hi = V(scene.room_hi());
  const Vec3 centre = 0.5 * (lo + hi);
  const Vec3 amp(0.22 * (hi.x() - lo.x()), 0.18 * (hi.y() - lo.y()), 0.12);
  const double ph[3] = {HashToUnit(seed * 3 + 1) * 6.283, HashToUnit(seed * 3 + 2) * 6.283,
                        HashToUnit(seed * 3 + 3) * 6.283};
  const double segment_frames = segment_s * fps;
  for (int i = 0; i < frames; ++i) {
    const double t = i / fps;
    const Vec3 eye = Vec3(centre.x(), centre.y(), 1.35) +
                     Vec3(amp.x() * std::sin(0.21 * t + ph[0]), amp.y() * std::sin(0.17 * t + ph[1]),
                          amp.z() * std::sin(0.31 * t + ph[2])) +
                     0.004 * Vec3(std::sin(7.3 * t), std::sin(6.1 * t + 1), std::sin(8.7 * t + 2));
    const double s = i / segment_frames;
    const std::size_t k = std::size_t(std::floor(s));
    // Eased over the whole segment: peak turn rates of about 1.5-2 degrees per frame at 30 Hz,
    // a brisk but steady hand.
    const double w = Ease(s - double(k));
    // Turn the viewing direction (not the target point) from one target to the next, so the
    // turn rate stays bounded even when the path between targets passes near the camera.
    auto dir = [&](const Vec3& t) {
      Vec3 d = (t - eye).normalized();
      if (std::abs(d.z()) > 0.7) {  // keep the end points well away from straight down/up
        const Vec3 h = Vec3(d.x(), d.y(), 0).norm() > 1e-6 ? Vec3(d.x(), d.y(), 0).normalized() : Vec3(1, 0, 0);
        d = (h * std::sqrt(1 - 0.49) + Vec3(0, 0, d.z() > 0 ? 0.7 : -0.7)).normalized();
      }
      return d;
    };
    const Eigen::Quaterniond qa = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitX(), dir(targets[k % targets.size()]));
    const Eigen::Quaterniond qb = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitX(), dir(targets[(k + 1) % targets.size()]));
    const Vec3 target = eye + qa.slerp(w, qb) * Vec3::UnitX();
    const double roll = 0.05 * std::sin(0.5 * t + ph[1]) + 0.004 * std::sin(9.1 * t);
    path.poses_.push_back(LookAt(eye, target, roll));
  }
  return path;
}

CameraPath CameraPath::Walk(const Scene& scene, std::uint32_t seed, int frames, double fps) {
  if (frames <= 0) throw SettingError("--frames", "must be positive");
  CameraPath path;
  path.fps_ = fps;
  const Vec3 lo = V(scene.room_lo()), hi = V(scene.room_hi());
  const Vec3 centre = 0.5 * (lo + hi);
  const double a = std::max(0.3, 0.5 * (hi.x() - lo.x()) - 2.3), b = std::max(0.3, 0.5 * (hi.y() - lo.y()) - 1.9);
  const double ph[3] = {HashToUnit(seed * 5 + 1) * 6.283, HashToUnit(seed * 5 + 2) * 6.283,
                        HashToUnit(seed * 5 + 3) * 6.283};
  const double speed = 0.4;                   // m/s
  const double omega = speed / (0.5 * (a + b));  // rad/s about the centre (about that pace)
  for (int i = 0; i < frames; ++i) {
    const double t = i / fps;
    const double th = ph[0] + omega * t;
    const Vec3 eye = centre + Vec3(a * std::cos(th), b * std::sin(th), 0) + Vec3(0, 0, 1.5 - centre.z()) +
                     Vec3(0, 0, 0.05 * std::sin(0.9 * t + ph[1])) +
                     0.004 * Vec3(std::sin(7.3 * t), std::sin(6.1 * t + 1), std::sin(8.7 * t + 2));
    // Outward normal of the ellipse, panned and tilted.
    const Vec3 out = Vec3(b * std::cos(th), a * std::sin(th), 0).normalized();
    const double yaw = 0.87 * std::sin(0.23 * t + ph[2]);               // ±50 degrees
    const double pitch = -0.2 + 0.18 * std::sin(0.31 * t + ph[1]);     // -21 to -1 degrees
    const Vec3 h = Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * out;
    const Vec3 dir = (h * std::cos(pitch) + Vec3(0, 0, std::sin(pitch))).normalized();
    const double roll = 0.05 * std::sin(0.5 * t + ph[1]) + 0.004 * std::sin(9.1 * t);
    path.poses_.push_back(LookAt(eye, eye + dir, roll));
  }
  return path;
}

CameraPath CameraPath::Static(Float3 eye, Float3 target, int frames, double fps) {
  if (frames <= 0) throw SettingError("--frames", "must be positive");
  CameraPath path;
  path.fps_ = fps;
  path.poses_.assign(std::size_t(frames), LookAt(V(eye), V(target)));
  return path;
}

CameraPath CameraPath::SweepView(const Scene& scene, int frames, double fps) {
  // Between a bright and a dark target, seen from the room's centre: both in view.
  const Float3 b = scene.bright_targets().front(), d = scene.dark_targets().front();
  const Float3 lo = scene.room_lo(), hi = scene.room_hi();
  const Float3 eye = {0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y) - 0.2f, 1.3f};
  const Float3 target = (b + d) * 0.5f;
  return Static(eye, target, frames, fps);
}

}  // namespace hdrf::sim
