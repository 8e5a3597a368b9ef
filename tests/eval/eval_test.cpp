#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "eval/eval.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

TEST(Eval, HornAlignmentRecoversARigidOffset) {
  std::vector<Pose> gt, est;
  Vec6 off;
  off << 0.3, -1.2, 0.5, 0.2, -0.4, 1.1;
  const Pose T = se3::Exp(off);
  for (int i = 0; i < 50; ++i) {
    Vec6 xi;
    xi << std::sin(0.1 * i), 0.05 * i, std::cos(0.07 * i), 0.01 * i, 0.02 * i, 0.0;
    gt.push_back(se3::Exp(xi));
    est.push_back(T * gt.back());
  }
  const auto e = eval::CompareTrajectories(est, gt);
  EXPECT_LT(e.ate_rmse_m, 1e-9);
  EXPECT_LT(e.rpe_trans_rmse_m, 1e-9);
  EXPECT_LT(se3::TranslationNorm(e.T_gt_est * T), 1e-9);
  // A known 1 cm error on one axis shows up as such.
  est[10].translation().x() += 0.01;
  EXPECT_NEAR(eval::CompareTrajectories(est, gt).ate_max_m, 0.01, 0.002);
}

}  // namespace
}  // namespace hdrf
