// Internal to hdrfusion_sensors: OpenNI2 frames copied into images, and colour paired with
// depth by timestamp. Shared by the live camera and .oni playback.
#pragma once

#include <OpenNI.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <optional>

#include "sensors/openni_camera.h"

namespace hdrf::sensors::detail {

// The frame's pixels (RGB888 colour or millimetre depth), timestamp in seconds, number.
inline LiveFrame CopyFrame(const openni::VideoFrameRef& ref) {
  LiveFrame f;
  f.timestamp = double(ref.getTimestamp()) * 1e-6;
  f.index = ref.getFrameIndex();
  const int w = ref.getWidth(), h = ref.getHeight();
  const auto* data = static_cast<const std::uint8_t*>(ref.getData());
  if (ref.getSensorType() == openni::SENSOR_COLOR) {
    f.color = ColorImage(w, h);
    for (int y = 0; y < h; ++y)
      std::memcpy(&f.color(0, y), data + std::size_t(y) * ref.getStrideInBytes(), std::size_t(w) * 3);
  } else {
    f.depth_mm = DepthRawImage(w, h);
    for (int y = 0; y < h; ++y)
      std::memcpy(&f.depth_mm(0, y), data + std::size_t(y) * ref.getStrideInBytes(), std::size_t(w) * 2);
  }
  return f;
}

// Colour and depth of the same moment: equal timestamps, or within half a frame period.
// A colour frame older than every depth frame has no partner and is counted as dropped;
// at most `pending` frames of each kind wait.
class FramePairer {
 public:
  explicit FramePairer(int fps, std::size_t pending = 4) : tolerance_(0.5 / std::max(1, fps)), pending_(pending) {}
  void AddColor(LiveFrame f) { color_.push_back(std::move(f)); }
  void AddDepth(LiveFrame f) { depth_.push_back(std::move(f)); }
  // The oldest complete pair, if any (colour frame with depth_mm filled in).
  std::optional<LiveFrame> Pop() {
    while (!color_.empty() && !depth_.empty()) {
      LiveFrame& c = color_.front();
      LiveFrame& d = depth_.front();
      if (std::abs(c.timestamp - d.timestamp) <= tolerance_) {
        c.depth_mm = std::move(d.depth_mm);
        depth_.pop_front();
        LiveFrame out = std::move(c);
        color_.pop_front();
        return out;
      }
      if (c.timestamp < d.timestamp) {
        color_.pop_front();
        ++unpaired_color_;
      } else {
        depth_.pop_front();
      }
    }
    while (color_.size() > pending_) {
      color_.pop_front();
      ++unpaired_color_;
    }
    while (depth_.size() > pending_) depth_.pop_front();
    return std::nullopt;
  }
  long unpaired_color() const { return unpaired_color_; }

 private:
  double tolerance_;
  std::size_t pending_;
  std::deque<LiveFrame> color_, depth_;
  long unpaired_color_ = 0;
};

}  // namespace hdrf::sensors::detail
