// Live and recorded-device frame sources for the engine (docs/sensors.md):
//   openni:[device=URI|SERIAL][,mode=vga|qvga][,ae=on|off][,awb=on|off][,exposure=MS]
//          [,exposure_raw=N][,gain=N][,frames=N]
//   PATH.oni   an OpenNI2 recording with its sidecars (PATH.oni.exposure.txt,
//              PATH.oni.sensor.json), stepped frame by frame
// and OpenAnySource, which adds them to the sequence and synthetic sources of io::OpenSource.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "pipeline/frame_source.h"
#include "sensors/openni_camera.h"
#include "sensors/profiles.h"

namespace hdrf::sensors {

struct LiveOptions {
  std::string device;  // URI or serial; empty: the first device
  CaptureMode mode;
  std::optional<bool> auto_exposure, auto_white_balance;  // unset: leave as the device has it
  std::optional<double> exposure_ms;                      // needs the profile's exposure unit
  std::optional<int> exposure_raw;
  std::optional<int> gain;
  int frames = -1;  // -1: until stopped
};
bool IsLiveSpec(const std::string& spec);
LiveOptions ParseLiveSpec(const std::string& spec);  // throws SettingError naming the key

class LiveFrameSource : public pipeline::FrameSource {
 public:
  // Opens the device, picks its profile, applies and verifies the exposure settings.
  explicit LiveFrameSource(LiveOptions options);
  int size() const override { return options_.frames; }
  // Waits for the next frame (2 s at most, then SensorError); DeviceLost when unplugged.
  bool Next(pipeline::FrameInput& frame) override;
  const SensorInfo& sensor() const override { return profile_.sensor; }
  std::string description() const override;

  OpenNiCamera& camera() { return *camera_; }
  const Profile& profile() const { return profile_; }
  // The next frame as the device gave it (for recording: no conversion to metres); the
  // same waits and errors as Next. Counts as delivered.
  LiveFrame NextFrame();
  // The raw frame behind the last Next (a scan that also records), and a frame's exposure in
  // milliseconds (none unless auto exposure was off and the profile gives the unit).
  const LiveFrame& last() const { return last_; }
  std::optional<double> ExposureMs(const LiveFrame& f) const;
  void ApplyExposure(const LiveOptions& o);  // the ae/awb/exposure/gain parts of o
  int delivered() const { return delivered_; }

 private:
  LiveOptions options_;
  std::unique_ptr<OpenNiCamera> camera_;
  Profile profile_;
  LiveFrame last_;
  int delivered_ = 0;
};

// Records the camera's streams to an .oni file (lossless) with the sidecars playback needs.
class OniRecording {
 public:
  OniRecording(const std::filesystem::path& file, OpenNiCamera& camera, const SensorInfo& sensor);
  ~OniRecording();
  // Notes a frame's exposure in the sidecar (frames the sidecar lacks play back as unknown).
  void NoteFrame(const LiveFrame& f, std::optional<double> exposure_ms, std::optional<double> gain);
  void Stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class OniPlaybackSource : public pipeline::FrameSource {
 public:
  explicit OniPlaybackSource(const std::filesystem::path& file);
  ~OniPlaybackSource() override;
  int size() const override;
  bool Next(pipeline::FrameInput& frame) override;
  const SensorInfo& sensor() const override;
  std::string description() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// io::OpenSource plus live devices ("openni:...") and .oni recordings.
std::unique_ptr<pipeline::FrameSource> OpenAnySource(const std::string& spec, const std::string& response);

}  // namespace hdrf::sensors
