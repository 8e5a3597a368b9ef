#include "common/se3.h"

#include <cmath>

#include "common/error.h"

namespace hdrf::se3 {

Mat3 Hat(const Vec3& w) {
  Mat3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

Pose Exp(const Vec6& xi) {
  const Vec3 v = xi.head<3>();
  const Vec3 w = xi.tail<3>();
  const double theta = w.norm();
  const Mat3 W = Hat(w);
  Mat3 R, V;
  if (theta < 1e-10) {
    R = Mat3::Identity() + W;
    V = Mat3::Identity() + 0.5 * W;
  } else {
    const double a = std::sin(theta) / theta;
    const double b = (1.0 - std::cos(theta)) / (theta * theta);
    const double c = (1.0 - a) / (theta * theta);
    R = Mat3::Identity() + a * W + b * W * W;
    V = Mat3::Identity() + b * W + c * W * W;
  }
  Pose T = Pose::Identity();
  T.linear() = R;
  T.translation() = V * v;
  return T;
}

Vec6 Log(const Pose& T) {
  const Eigen::AngleAxisd aa(T.rotation());
  const double theta = aa.angle();
  const Vec3 w = aa.axis() * theta;
  const Mat3 W = Hat(w);
  Mat3 V_inv;
  if (theta < 1e-10) {
    V_inv = Mat3::Identity() - 0.5 * W;
  } else {
    const double half = 0.5 * theta;
    const double k = (1.0 - half * std::cos(half) / std::sin(half)) / (theta * theta);
    V_inv = Mat3::Identity() - 0.5 * W + k * W * W;
  }
  Vec6 xi;
  xi.head<3>() = V_inv * T.translation();
  xi.tail<3>() = w;
  return xi;
}

Pose FromTranslationQuaternion(const Vec3& t, double qx, double qy, double qz, double qw) {
  Eigen::Quaterniond q(qw, qx, qy, qz);
  const double n = q.norm();
  if (!(n > 1e-12) || !std::isfinite(n)) throw Error("quaternion has zero or non-finite norm");
  q.normalize();
  Pose T = Pose::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = t;
  return T;
}

double RotationAngle(const Pose& T) { return Eigen::AngleAxisd(T.rotation()).angle(); }
double TranslationNorm(const Pose& T) { return T.translation().norm(); }

Pose Orthonormalized(const Pose& T) {
  Pose out = T;
  out.linear() = Eigen::Quaterniond(T.rotation()).normalized().toRotationMatrix();
  return out;
}

}  // namespace hdrf::se3
