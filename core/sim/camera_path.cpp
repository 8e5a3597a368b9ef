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
  const Vec3 f = (target - eye).normalized();
  Vec3 up(0, 0, 1);
  if (std::abs(f.dot(up)) > 0.99) up = Vec3(0, 1, 0);
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
    const double w = Ease(std::clamp((s - double(k)) * 1.6 - 0.3, 0.0, 1.0));
    const Vec3 target = (1 - w) * targets[k % targets.size()] + w * targets[(k + 1) % targets.size()];
    const double roll = 0.05 * std::sin(0.5 * t + ph[1]) + 0.004 * std::sin(9.1 * t);
    path.poses_.push_back(LookAt(eye, target, roll));
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
