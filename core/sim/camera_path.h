// Camera trajectories through a scene, with timestamps: smooth handheld-like sweeps between
// bright and dark places, and a static camera for exposure sweeps.
#pragma once

#include <cstdint>
#include <vector>

#include "common/se3.h"
#include "sim/scene.h"

namespace hdrf::sim {

class CameraPath {
 public:
  // Looks at the scene's bright and dark targets in turn (a new one every `segment_s`
  // seconds, eased in and out), from positions drifting around the room's centre, with a
  // small hand tremor. Deterministic for a seed.
  static CameraPath Handheld(const Scene& scene, std::uint32_t seed, int frames, double fps = 30.0,
                             double segment_s = 4.0);
  // Walking round a large room (the hall): the eye goes round an ellipse about the room's
  // centre (2.3 m from the end walls, 1.9 m from the side walls) at a walking pace of
  // 0.4 m/s, facing out towards the walls and the furniture along them within the
  // sensor's depth range, panning ±50 degrees to either side and tilting down to the floor
  // and up to the walls, with a small hand tremor. Deterministic for a seed.
  static CameraPath Walk(const Scene& scene, std::uint32_t seed, int frames, double fps = 30.0);
  // One pose for every frame: from `eye` towards `target`.
  static CameraPath Static(Float3 eye, Float3 target, int frames, double fps = 30.0);
  // The static view used for exposure sweeps of a scene (window and shadow both in view).
  static CameraPath SweepView(const Scene& scene, int frames, double fps = 30.0);

  int size() const { return int(poses_.size()); }
  const Pose& T_world_camera(int i) const { return poses_[std::size_t(i)]; }
  double timestamp(int i) const { return t0_ + i / fps_; }

 private:
  std::vector<Pose> poses_;
  double fps_ = 30.0;
  double t0_ = 1.0;
};

// Camera-to-world pose at `eye` looking at `target` (camera x right, y down, z forward;
// world z up), rolled by `roll` radians about the viewing axis.
Pose LookAt(const Vec3& eye, const Vec3& target, double roll = 0.0);

}  // namespace hdrf::sim
