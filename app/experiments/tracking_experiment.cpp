#include "tracking_experiment.h"

#include <chrono>

#include "common/error.h"
#include "pipeline/scan_session.h"

namespace hdrf::experiments {

std::vector<TrackerSpec> ExperimentTrackers() {
  using K = tracking::TrackerKind;
  std::vector<TrackerSpec> v;
  v.push_back({"intensity", "raw intensity, brightness constancy (frame to frame)", false, BaselineKind::kNcc,
               K::kIntensity, false});
  v.push_back({"ncc", "NCC on 9x9 patches of raw intensity, Scandaroli-style (frame to frame)", true,
               BaselineKind::kNcc, K::kNr, false});
  v.push_back({"joint-exposure", "radiance with a gain estimated with the pose, Meilland-style (frame to frame)",
               true, BaselineKind::kJointExposure, K::kNr, false});
  v.push_back({"nr-f2f", "normalized radiance, frame to frame", false, BaselineKind::kNcc, K::kNr, false});
  v.push_back({"nr-f2m", "normalized radiance, frame to model (HDRFusion)", false, BaselineKind::kNcc, K::kNr, true});
  v.push_back({"icp", "point-to-plane ICP, frame to model", false, BaselineKind::kNcc, K::kIcp, true});
  v.push_back({"nr+icp", "normalized radiance + ICP, frame to model (HDRFusion default)", false, BaselineKind::kNcc,
               K::kNrIcp, true});
  return v;
}

TrackerRun RunTracker(const TrackerSpec& spec, const std::vector<pipeline::FrameInput>& frames,
                      const PinholeCamera& camera, const SensorInfo& sensor,
                      const pipeline::PipelineOptions& engine, const std::function<void(int)>& progress) {
  TrackerRun run;
  run.id = spec.id;
  run.poses.reserve(frames.size());
  const auto t0 = std::chrono::steady_clock::now();
  if (spec.baseline) {
    BaselineTracker tracker(spec.baseline_kind, camera, sensor);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const BaselineStep s = tracker.Process(frames[i].color, frames[i].depth_m);
      run.poses.push_back(s.T_world_camera);
      run.lost += s.lost;
      if (progress) progress(int(i + 1));
    }
  } else {
    pipeline::PipelineOptions o = engine;
    o.tracker.kind = spec.kind;
    o.tracker.frame_to_model = spec.frame_to_model;
    pipeline::ScanSession session(o, camera, sensor);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      session.Process(frames[i]);
      if (progress) progress(int(i + 1));
    }
    run.poses = session.poses();
    run.lost = session.lost();
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

PerFrameError PerFrameErrors(const std::vector<Pose>& est, const std::vector<Pose>& truth, const Pose& T_gt_est) {
  if (est.size() != truth.size()) throw Error("per-frame errors: trajectories of different lengths");
  PerFrameError e;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Pose aligned = T_gt_est * est[i];
    const Pose d = truth[i].inverse() * aligned;
    e.trans_m.push_back((aligned.translation() - truth[i].translation()).norm());
    e.rot_deg.push_back(se3::RotationAngle(d) * 180.0 / M_PI);
  }
  return e;
}

}  // namespace hdrf::experiments
