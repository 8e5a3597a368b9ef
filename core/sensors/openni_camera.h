// Live RGB-D cameras through OpenNI2 (docs/sensors.md): listing, opening by URI or serial,
// colour and depth paired by timestamp, exposure control applied after the stream starts
// and verified, hot-plug events. Every failure is a SensorError naming the device.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/image.h"

namespace hdrf::sensors {

class SensorError : public Error {
 public:
  using Error::Error;
};

// The device went away (unplugged) while it was being read.
class DeviceLost : public SensorError {
 public:
  using SensorError::SensorError;
};

struct DeviceEntry {
  std::string name, vendor, uri, serial;  // serial empty when the device would not open
};

struct CaptureMode {
  int width = 640, height = 480, fps = 30;
};
// "vga" (640x480) or "qvga" (320x240), 30 Hz.
CaptureMode ParseCaptureMode(const std::string& name);

// What the camera reports of its colour settings.
struct ExposureState {
  bool auto_exposure = true, auto_white_balance = true;
  int exposure_raw = 0;  // the device's unit (docs/sensors.md)
  int gain = 0;          // 100 = unity
};

struct LiveFrame {
  ColorImage color;
  DepthRawImage depth_mm;          // millimetres, registered to colour; 0 = no data
  double timestamp = 0;            // seconds, device clock
  int index = 0;                   // the device's colour frame number
  std::optional<int> exposure_raw; // in force when the frame was taken (AE off, settled)
  std::optional<int> gain;          // OpenNI2's units: hundredths (100 is unit gain)
  LiveFrame Clone() const {
    return {color.Clone(), depth_mm.Clone(), timestamp, index, exposure_raw, gain};
  }
  // The gain as a linear factor (1 at unit gain), as recordings store it and the engine
  // multiplies a frame's exposure by it.
  std::optional<double> GainFactor() const { return gain ? std::optional<double>(*gain / 100.0) : std::nullopt; }
};

// OpenNI2 is initialised once per process and never shut down (driver threads outlive
// objects in some drivers; process exit cleans up). Throws SensorError if it cannot start.
void EnsureOpenNi();

// Devices connected now. Opens each briefly to read its serial (a device in use by another
// program is listed with an empty serial); a device in `known` (one this process has open)
// is taken from there, not opened again.
std::vector<DeviceEntry> ListDevices(const std::vector<DeviceEntry>& known = {});

// Connect and disconnect events, delivered on OpenNI's threads (forward them; do not block).
class HotplugMonitor {
 public:
  using Callback = std::function<void(const std::string& uri, bool connected)>;
  explicit HotplugMonitor(Callback callback);
  ~HotplugMonitor();
  HotplugMonitor(const HotplugMonitor&) = delete;
  HotplugMonitor& operator=(const HotplugMonitor&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class OpenNiCamera {
 public:
  // `id`: a URI, a serial, or "" for the first device. Starts colour and depth at `mode`,
  // depth registered to colour where the device can, frame sync on, mirroring off.
  static std::unique_ptr<OpenNiCamera> Open(const std::string& id, CaptureMode mode);
  ~OpenNiCamera();

  const DeviceEntry& entry() const;
  CaptureMode mode() const;
  bool depth_registered_by_device() const;  // false: the device could not register depth
  // False when the colour stream has no camera settings (no exposure control).
  bool has_camera_settings() const;

  // Each applies the setting, waits for frames under it and reads it back; throws
  // SensorError when the device has no camera settings or does not take the value.
  void SetAutoExposure(bool on);
  void SetAutoWhiteBalance(bool on);
  void SetExposure(int raw);
  void SetGain(int gain);
  ExposureState exposure() const;

  // The next colour frame with its depth partner (same timestamp, or within half a frame
  // period). nullopt on timeout; throws DeviceLost once the device is unplugged.
  std::optional<LiveFrame> Read(std::chrono::milliseconds timeout);
  // Colour frames the device numbered but that never reached Read (gaps, full queue).
  long dropped() const;
  bool lost() const;
  // Discards the frames waiting to be read (taken before a change of settings).
  void Flush();

  // Records both streams to an OpenNI2 .oni file, lossless, until stopped (or destroyed).
  void StartOniRecording(const std::string& file);
  void StopOniRecording();

 private:
  OpenNiCamera();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hdrf::sensors
