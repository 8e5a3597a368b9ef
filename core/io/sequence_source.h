// A recorded sequence (docs/formats.md) as a pipeline frame source.
#pragma once

#include "common/message.h"
#include "io/sequence.h"
#include "pipeline/frame_source.h"

namespace hdrf::io {

class SequenceFrameSource : public pipeline::FrameSource {
 public:
  explicit SequenceFrameSource(const std::filesystem::path& folder)
      : seq_(folder), sensor_(seq_.sensor()) {}
  int size() const override { return int(seq_.size()); }
  bool Next(pipeline::FrameInput& f) override {
    if (next_ >= seq_.size()) return false;
    Frame fr = seq_.ReadFrame(next_++);
    f.color = std::move(fr.color);
    f.depth_m = std::move(fr.depth_m);
    f.timestamp = fr.info.timestamp;
    // The signal grows with exposure time times analog gain (a linear factor of the sensor's
    // amplifier): the engine takes the product as the frame's exposure, so a gain that
    // changes between frames is not mistaken for a change of the light.
    f.exposure_ms = fr.info.exposure_ms;
    if (f.exposure_ms && fr.info.gain) *f.exposure_ms *= *fr.info.gain;
    f.T_world_camera_true = fr.info.T_world_camera;
    return true;
  }
  const SensorInfo& sensor() const override { return sensor_; }
  // The documented fallback for sequences without calibration (`--response srgb`): the
  // sRGB curve, with a warning that says so.
  void AssumeSrgbResponse() {
    sensor_.response = radiometry::InverseResponse::Srgb();
    sensor_.warnings.push_back(Say(words::kSrgbAssumed, {(seq_.folder() / "sensor.json").string()}));
  }
  std::string description() const override { return "sequence " + seq_.folder().string(); }
  bool Skip(int n) override {
    if (n < 0 || next_ + std::size_t(n) > seq_.size()) return false;
    next_ += std::size_t(n);
    return true;
  }
  const SequenceReader& reader() const { return seq_; }

 private:
  SequenceReader seq_;
  SensorInfo sensor_;
  std::size_t next_ = 0;
};

}  // namespace hdrf::io
