// Trajectory and model accuracy against ground truth.
#pragma once

#include <vector>

#include "common/se3.h"

namespace hdrf::eval {

struct TrajectoryError {
  std::size_t pairs = 0;
  double ate_rmse_m = 0, ate_median_m = 0, ate_max_m = 0;  // after rigid alignment (Horn)
  double rpe_trans_rmse_m = 0, rpe_rot_rmse_deg = 0;       // frame-to-frame relative error
  Pose T_gt_est = Pose::Identity();                        // the alignment found
};

// estimated[i] and truth[i] are poses of the same frame (already associated by time).
TrajectoryError CompareTrajectories(const std::vector<Pose>& estimated,
                                    const std::vector<Pose>& truth);

}  // namespace hdrf::eval
