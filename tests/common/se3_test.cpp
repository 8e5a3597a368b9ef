#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/error.h"
#include "common/se3.h"

namespace hdrf {
namespace {

TEST(Se3, ExpLogRoundTripOverManyTwists) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0;
  for (int k = 0; k < 500; ++k) {
    Vec6 xi;
    for (int i = 0; i < 6; ++i) xi[i] = u(rng) * (i < 3 ? 2.0 : 1.5);
    const Vec6 back = se3::Log(se3::Exp(xi));
    worst = std::max(worst, (back - xi).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(Se3, ExpOfSmallTwistIsFirstOrderAccurate) {
  Vec6 xi;
  xi << 1e-12, -2e-12, 3e-12, 1e-13, 0, -1e-13;
  const Pose T = se3::Exp(xi);
  EXPECT_NEAR((T.translation() - xi.head<3>()).norm(), 0, 1e-20);
  EXPECT_NEAR(se3::RotationAngle(T), xi.tail<3>().norm(), 1e-15);
}

TEST(Se3, RotationByKnownAngleAndAxis) {
  Vec6 xi = Vec6::Zero();
  xi[5] = M_PI / 2;  // 90 degrees about z
  const Pose T = se3::Exp(xi);
  const Vec3 x = T.rotation() * Vec3::UnitX();
  EXPECT_NEAR((x - Vec3::UnitY()).norm(), 0, 1e-12);
  EXPECT_NEAR(se3::RotationAngle(T), M_PI / 2, 1e-12);
}

TEST(Se3, QuaternionIsNormalisedAndZeroRejected) {
  const Pose T = se3::FromTranslationQuaternion(Vec3(1, 2, 3), 0, 0, 2, 0);  // 180 deg about z
  EXPECT_NEAR((T.rotation() * Vec3::UnitX() + Vec3::UnitX()).norm(), 0, 1e-12);
  EXPECT_NEAR(T.translation().z(), 3.0, 0);
  EXPECT_THROW(se3::FromTranslationQuaternion(Vec3::Zero(), 0, 0, 0, 0), Error);
}

TEST(Se3, OrthonormalizedRepairsDrift) {
  Pose T = se3::Exp((Vec6() << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6).finished());
  T.linear() *= 1.001;
  const Pose R = se3::Orthonormalized(T);
  EXPECT_NEAR((R.rotation().transpose() * R.rotation() - Mat3::Identity()).norm(), 0, 1e-12);
}

}  // namespace
}  // namespace hdrf
