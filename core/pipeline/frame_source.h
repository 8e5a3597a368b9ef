// Where frames come from: a recorded sequence, the synthetic sensor, later a live OpenNI2
// camera. The pipeline and the studio see only this interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "pipeline/pipeline.h"
#include "radiometry/sensor.h"
#include "sim/synthetic_source.h"

namespace hdrf::pipeline {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual int size() const = 0;                 // frames available (-1: unbounded)
  virtual bool Next(FrameInput& frame) = 0;     // false when exhausted; throws on bad data
  virtual const SensorInfo& sensor() const = 0;
  virtual std::string description() const = 0;
  // Passes over the next n frames (a resumed scan starts where it stopped); false where the
  // source ran out first. Reads and drops them unless a source can seek.
  virtual bool Skip(int n) {
    FrameInput f;
    for (int i = 0; i < n; ++i)
      if (!Next(f)) return false;
    return true;
  }
};

// The synthetic sensor as a frame source (exposures and true poses attached).
class SyntheticFrameSource : public FrameSource {
 public:
  explicit SyntheticFrameSource(sim::SimOptions o) : src_(std::move(o)), sensor_(src_.sensor()) {}
  int size() const override { return src_.size(); }
  bool Next(FrameInput& f) override {
    if (src_.done()) return false;
    sim::SimFrame s = src_.Next();
    f.color = std::move(s.color);
    f.depth_m = DepthImage(s.depth.width(), s.depth.height());
    const float inv = float(1.0 / src_.options().depth_scale);
    for (std::size_t i = 0; i < s.depth.size(); ++i) f.depth_m[i] = float(s.depth[i]) * inv;
    f.timestamp = s.timestamp;
    f.exposure_ms = s.exposure_ms;
    f.T_world_camera_true = s.T_world_camera;
    return true;
  }
  const SensorInfo& sensor() const override { return sensor_; }
  std::string description() const override {
    return "synthetic scene '" + src_.options().scene + "', seed " + std::to_string(src_.options().seed);
  }

 private:
  sim::SyntheticSource src_;
  SensorInfo sensor_;
};

// Every frame of a bounded source, read up front (benchmarks and figures time or compare
// the engine, not the source).
inline std::vector<FrameInput> ReadAll(FrameSource& src) {
  std::vector<FrameInput> frames;
  FrameInput f;
  while ((src.size() < 0 || int(frames.size()) < src.size()) && src.Next(f)) frames.push_back(std::move(f));
  return frames;
}

}  // namespace hdrf::pipeline
