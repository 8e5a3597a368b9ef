// SE(3) helpers on Eigen. Poses are rigid transforms named by the frames they map
// between: T_world_camera maps camera-frame points into the world frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hdrf {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;  // twist: (translation v, rotation w)
using Pose = Eigen::Isometry3d;

namespace se3 {

// Skew-symmetric matrix of w: Hat(w) * x == w.cross(x).
Mat3 Hat(const Vec3& w);

// Exponential map of a twist (v, w) to a rigid transform.
Pose Exp(const Vec6& xi);

// Logarithm: the twist (v, w) whose exponential is T (rotation angle in [0, pi]).
Vec6 Log(const Pose& T);

// Pose from translation and quaternion (x, y, z, w order as in TUM files); the quaternion
// is normalised. Throws hdrf::Error for a zero quaternion.
Pose FromTranslationQuaternion(const Vec3& t, double qx, double qy, double qz, double qw);

// Rotation angle of T in radians, and translation length in metres.
double RotationAngle(const Pose& T);
double TranslationNorm(const Pose& T);

// Re-orthonormalises the rotation part (after accumulating many small updates).
Pose Orthonormalized(const Pose& T);

}  // namespace se3
}  // namespace hdrf

#include "common/vec.h"

namespace hdrf {
// Float copy of a pose for per-element code.
inline RigidTransform ToRigidTransform(const Pose& T) {
  RigidTransform out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.r[3 * i + j] = float(T.linear()(i, j));
  out.t = {float(T.translation().x()), float(T.translation().y()), float(T.translation().z())};
  return out;
}
}  // namespace hdrf
