// Sensor profiles: one calibration (sensor.json, docs/formats.md) per device serial, kept
// in the user's data folder and chosen automatically when that device connects; the
// built-in Xtion profile otherwise, with a warning that its response is not this device's.
#pragma once

#include <filesystem>
#include <string>

#include "radiometry/sensor.h"
#include "sensors/openni_camera.h"

namespace hdrf::sensors {

// $XDG_DATA_HOME/hdrfusion/sensors, else ~/.local/share/hdrfusion/sensors.
std::filesystem::path ProfileFolder();
// The profile file a serial is stored under (the folder above, the serial made file-safe).
std::filesystem::path ProfilePath(const std::string& serial);

struct Profile {
  SensorInfo sensor;           // camera scaled to the capture mode
  std::filesystem::path file;  // empty: the built-in profile
  bool own = false;            // measured on this device
};

// The profile for a device at a capture mode. Warnings (fallback profile, no exposure unit)
// go into sensor.warnings. Throws InputError for a profile file that is malformed, or whose
// camera cannot be scaled to the mode (another aspect ratio).
Profile ProfileFor(const DeviceEntry& device, CaptureMode mode);

// Stores a calibration as this serial's profile (atomically); returns the file.
std::filesystem::path SaveProfile(const std::string& serial, SensorInfo sensor);

}  // namespace hdrf::sensors
