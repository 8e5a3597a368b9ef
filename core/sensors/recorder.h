// Lossless recording of live frames to the project's sequence layout (docs/formats.md) on a
// writer thread behind a bounded queue. A frame the queue cannot take is counted as dropped,
// never lost silently; a write failure (full disk) ends the recording with every written
// frame complete and the lists consistent, and says why.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "radiometry/sensor.h"
#include "sensors/openni_camera.h"

namespace hdrf::io {
class SequenceWriter;
}

namespace hdrf::sensors {

struct RecordingStats {
  long written = 0;       // frames complete on disk
  long dropped = 0;       // frames the queue could not take (or that arrived after a failure)
  double bytes = 0;       // image bytes written
  double seconds = 0;     // since the first frame was queued
  std::string error;      // why the recording ended early; empty while it is fine
};

class SequenceRecorder {
 public:
  // Creates `folder` (absent or empty) and its sensor.json. `queue` frames at most wait.
  SequenceRecorder(const std::filesystem::path& folder, const SensorInfo& sensor, std::size_t queue = 48);
  ~SequenceRecorder();  // Finish()
  SequenceRecorder(const SequenceRecorder&) = delete;
  SequenceRecorder& operator=(const SequenceRecorder&) = delete;

  // Queues a frame (exposure_ms: the exposure in force, if known). Never blocks; false when
  // the frame was dropped (queue full, or the recording has failed).
  bool Push(LiveFrame frame, std::optional<double> exposure_ms, std::optional<double> gain = std::nullopt);
  // Writes what is queued and closes the lists.
  RecordingStats Finish();
  RecordingStats stats() const;
  bool failed() const;
  const std::filesystem::path& folder() const { return folder_; }

 private:
  struct Item {
    LiveFrame frame;
    std::optional<double> exposure_ms, gain;
  };
  void Run();
  void Write(const Item& item);

  std::filesystem::path folder_;
  std::unique_ptr<io::SequenceWriter> writer_;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Item> queue_;
  RecordingStats stats_;
  bool closing_ = false, failed_ = false, started_ = false;
  double t0_ = 0;
  std::thread thread_;
};

}  // namespace hdrf::sensors
