// One scan: the per-frame system and everything a scan accumulates (the trajectory, the
// per-frame reports, exposures and stage times). The scan command, the studio, the engine
// benchmark and the experiments all run frames through one of these, so that the totals
// they report are computed once, here.
#pragma once

#include <optional>
#include <vector>

#include "pipeline/keyframes.h"
#include "pipeline/pipeline.h"

namespace hdrf::pipeline {

class ScanSession {
 public:
  ScanSession(const PipelineOptions& options, const PinholeCamera& camera,
              const SensorInfo& sensor, const KeyframeOptions& keyframes = {});

  // Runs one frame and records its report.
  const FrameReport& Process(const FrameInput& frame);
  // Takes up a saved scan (a project reopened) on a fresh session: its model, where it
  // stopped, its per-frame reports and its keyframes; the next Process() goes on as if the
  // scan had never stopped. Throws hdrf::Error where they do not fit together.
  void Resume(const volume::Volume& model, const ResumePoint& point, std::vector<FrameReport> reports,
              std::vector<Keyframe> keyframes, int keyframes_thinned);
  int keyframes_thinned() const { return keyframes_.thinned(); }

  Pipeline& pipeline() { return pipeline_; }
  const Pipeline& pipeline() const { return pipeline_; }

  const std::vector<FrameReport>& reports() const { return reports_; }
  // The frames kept for texturing (keyframes.h).
  const std::vector<Keyframe>& keyframes() const { return keyframes_.keyframes(); }
  const SensorInfo& sensor() const { return sensor_; }
  int frames() const { return int(reports_.size()); }
  int lost() const { return lost_; }  // frames with no pose (waiting to anchor included)
  // Frames by what became of them (FrameState), and how often the scan was found again from
  // an earlier view after a loss.
  int count(FrameState s) const;
  int relocalisations() const;
  int fused() const;
  // One pose per processed frame (a lost frame keeps the last good pose), with timestamps.
  std::vector<Pose> poses() const;
  std::vector<double> timestamps() const;
  // Stage times summed over every frame, and their mean per frame.
  const StageTimes& total_ms() const { return total_ms_; }
  StageTimes mean_ms() const;
  double frames_per_second() const;  // frames over the summed stage time
  // The median of |estimated / reported - 1| over frames with both an estimate and a
  // sensor-reported exposure (not the first); none where no frame had both.
  std::optional<double> exposure_median_relative_error() const;

 private:
  Pipeline pipeline_;
  SensorInfo sensor_;
  KeyframeSelector keyframes_;
  std::vector<FrameReport> reports_;
  StageTimes total_ms_;
  int lost_ = 0;
};

}  // namespace hdrf::pipeline
