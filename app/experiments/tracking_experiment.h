// The paper's tracking experiment: one sequence, several trackers side by side, each
// trajectory compared with the ground truth (ATE, RPE, per-frame errors).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "baseline_trackers.h"
#include "eval/eval.h"
#include "pipeline/pipeline.h"

namespace hdrf::experiments {

struct TrackerSpec {
  std::string id;     // short name used in files and tables: "nr-f2m", "ncc", ...
  std::string label;  // what it is, for tables
  bool baseline = false;               // true: a BaselineTracker, else the engine
  BaselineKind baseline_kind = BaselineKind::kNcc;
  tracking::TrackerKind kind = tracking::TrackerKind::kNrIcp;
  bool frame_to_model = true;
};

// The seven trackers of the experiment, in table order: intensity, NCC, joint exposure,
// NR frame-to-frame, NR frame-to-model, ICP, NR + ICP.
std::vector<TrackerSpec> ExperimentTrackers();

struct TrackerRun {
  std::string id;
  std::vector<Pose> poses;  // one per frame, world = first camera
  int lost = 0;             // frames the tracker itself reported lost
  double seconds = 0;       // wall time of tracking (and, for the engine, fusion and ray casting)
};

// Runs one tracker over frames already in memory; `progress(done)` after each frame.
// `engine` holds the volume and other settings of the engine runs (its tracker is replaced).
TrackerRun RunTracker(const TrackerSpec& spec, const std::vector<pipeline::FrameInput>& frames,
                      const PinholeCamera& camera, const SensorInfo& sensor,
                      const pipeline::PipelineOptions& engine,
                      const std::function<void(int)>& progress = {});

// Per-frame errors after the rigid alignment of CompareTrajectories: translation (m) and
// rotation (degrees) of each aligned pose against the truth.
struct PerFrameError {
  std::vector<double> trans_m, rot_deg;
};
PerFrameError PerFrameErrors(const std::vector<Pose>& estimated, const std::vector<Pose>& truth,
                             const Pose& T_gt_est);

}  // namespace hdrf::experiments
