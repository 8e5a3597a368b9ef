// Trajectory and model accuracy against ground truth.
#pragma once

#include <vector>

#include "common/se3.h"
#include "mesh/mesh.h"
#include "sim/scene.h"

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

// The model against the synthetic scene: distance of mesh vertices to the true surface, and
// the fused radiance against the true radiance after one scale per channel (the model's
// units are the first frame's radiance units), in stops.
struct ModelError {
  std::size_t vertices = 0, radiance_samples = 0;
  double mesh_median_distance_m = 0;
  double radiance_median_stops = 0, within_01_stop = 0, within_025_stop = 0;
  // Dynamic range, log2 of the 99th over the 1st percentile of luminance over the same
  // vertices: of the fused radiance (after the scales) and of the true radiance there.
  double model_range_stops = 0, true_range_stops = 0;
  double scale[3] = {1, 1, 1};
};
// log2 of the `hi` over the `lo` quantile of positive values (0 when fewer than 2).
double RangeStops(std::vector<double> values, double lo = 0.01, double hi = 0.99);

// T_scene_model maps model (first camera) coordinates into the scene; at most
// `max_samples` vertices are used (evenly spaced).
ModelError CompareModel(const mesh::Mesh& m, const sim::Scene& scene, const Pose& T_scene_model,
                        std::size_t max_samples = 200000);

// Surface completeness: the share of `points` (true surface samples, in the mesh's frame)
// within `tolerance` metres of a mesh triangle (exact point-to-triangle distance).
struct Completeness {
  std::size_t points = 0, within = 0;
  double fraction() const { return points ? double(within) / double(points) : 0.0; }
};
Completeness SurfaceCompleteness(const mesh::Mesh& m, const std::vector<Float3>& points, double tolerance);

}  // namespace hdrf::eval
