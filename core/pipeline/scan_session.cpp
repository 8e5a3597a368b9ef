#include "pipeline/scan_session.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.h"

namespace hdrf::pipeline {

ScanSession::ScanSession(const PipelineOptions& options, const PinholeCamera& camera,
                         const SensorInfo& sensor, const KeyframeOptions& keyframes)
    : pipeline_(options, camera, sensor), sensor_(sensor), keyframes_(keyframes) {
  sensor_.camera = camera;
}

const FrameReport& ScanSession::Process(const FrameInput& frame) {
  reports_.push_back(pipeline_.Process(frame));
  const FrameReport& r = reports_.back();
  total_ms_ += r.ms;
  lost_ += r.tracking.lost;
  keyframes_.Offer(r, frame.color);
  return r;
}

void ScanSession::Resume(const volume::Volume& model, const ResumePoint& point, std::vector<FrameReport> reports,
                         std::vector<Keyframe> keyframes, int keyframes_thinned) {
  if (!reports_.empty()) throw Error("a scan can only be resumed on a fresh session");
  if (int(reports.size()) != point.frames)
    throw Error("the saved scan has " + std::to_string(reports.size()) + " frame reports for " +
                std::to_string(point.frames) + " frames");
  for (std::size_t i = 0; i < reports.size(); ++i)
    if (reports[i].index != int(i)) throw Error("the saved frame reports are out of order at " + std::to_string(i));
  pipeline_.Resume(model, point);
  keyframes_.Restore(std::move(keyframes), keyframes_thinned);
  reports_ = std::move(reports);
  total_ms_ = {};
  lost_ = 0;
  for (const FrameReport& r : reports_) {
    total_ms_ += r.ms;
    lost_ += r.tracking.lost;
  }
}

int ScanSession::count(FrameState s) const {
  return int(std::count_if(reports_.begin(), reports_.end(), [&](const FrameReport& r) { return r.state == s; }));
}

int ScanSession::fused() const {
  return int(std::count_if(reports_.begin(), reports_.end(), [](const FrameReport& r) { return r.fused; }));
}

int ScanSession::relocalisations() const {
  int n = 0;
  // A run of relocalised frames is one relocalisation, whether the frame before it was lost
  // or its own tracking failed and an earlier view found the pose.
  for (std::size_t i = 0; i < reports_.size(); ++i)
    n += reports_[i].state == FrameState::kRelocalised && (i == 0 || reports_[i - 1].state != FrameState::kRelocalised);
  return n;
}

std::vector<Pose> ScanSession::poses() const {
  std::vector<Pose> p;
  p.reserve(reports_.size());
  for (const FrameReport& r : reports_) p.push_back(r.T_world_camera);
  return p;
}

std::vector<double> ScanSession::timestamps() const {
  std::vector<double> t;
  t.reserve(reports_.size());
  for (const FrameReport& r : reports_) t.push_back(r.timestamp);
  return t;
}

StageTimes ScanSession::mean_ms() const {
  return reports_.empty() ? StageTimes{} : total_ms_ / double(frames());
}

double ScanSession::frames_per_second() const {
  const double ms = total_ms_.total();
  return ms > 0 ? 1000.0 * double(frames()) / ms : 0.0;
}

std::optional<double> ScanSession::exposure_median_relative_error() const {
  std::vector<double> err;
  for (const FrameReport& r : reports_)
    if (r.exposure_ratio_reported && r.index > 0 && r.exposure_samples > 0)
      err.push_back(std::abs(r.exposure_ratio / *r.exposure_ratio_reported - 1));
  if (err.empty()) return std::nullopt;
  std::nth_element(err.begin(), err.begin() + std::ptrdiff_t(err.size() / 2), err.end());
  return err[err.size() / 2];
}

}  // namespace hdrf::pipeline
