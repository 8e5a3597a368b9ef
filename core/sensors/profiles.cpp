#include "sensors/profiles.h"

#include <cstdlib>

#include "common/message.h"
#include "io/sensor_json.h"
#include "sim/builtin_sensor.h"

namespace hdrf::sensors {

namespace fs = std::filesystem;

fs::path ProfileFolder() {
  if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg && fs::path(xdg).is_absolute())
    return fs::path(xdg) / "hdrfusion" / "sensors";
  const char* home = std::getenv("HOME");
  return fs::path(home && *home ? home : "/tmp") / ".local" / "share" / "hdrfusion" / "sensors";
}

fs::path ProfilePath(const std::string& serial) {
  std::string safe;
  for (char c : serial) safe += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  if (safe.empty()) safe = "unknown";
  return ProfileFolder() / (safe + ".json");
}

Profile ProfileFor(const DeviceEntry& device, CaptureMode mode) {
  Profile p;
  const fs::path file = device.serial.empty() ? fs::path() : ProfilePath(device.serial);
  if (!file.empty() && fs::exists(file)) {
    p.sensor = io::ReadSensorJson(file);
    p.file = file;
    p.own = true;
    if (!p.sensor.response)
      throw InputError(file, "the profile of device " + device.serial + " has no 'response' calibration");
  } else {
    p.sensor = sim::BuiltinXtionProfile();
    p.sensor.synthetic.reset();
    const std::string stores = file.empty() ? ProfileFolder().string() + "/<serial>.json" : file.string();
    p.sensor.warnings.push_back(
        device.serial.empty()
            ? Say(words::kNoProfile, {device.name, ProfileFolder().string(), stores})
            : Say(words::kNoProfileSerial, {device.name, device.serial, ProfileFolder().string(), stores}));
  }
  // Scale the camera to the capture mode (the same sensor binned or cropped to another size
  // keeps its aspect; anything else is refused rather than guessed).
  PinholeCamera& c = p.sensor.camera;
  if (c.width != mode.width || c.height != mode.height) {
    const double sx = double(mode.width) / c.width, sy = double(mode.height) / c.height;
    if (std::abs(sx - sy) > 1e-9)
      throw InputError(p.file.empty() ? fs::path("built-in profile") : p.file,
                       "camera is " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                           " and cannot be scaled to the capture mode " + std::to_string(mode.width) + "x" +
                           std::to_string(mode.height) + " (another aspect ratio)");
    c.fx = float(c.fx * sx);
    c.fy = float(c.fy * sy);
    c.cx = float((c.cx + 0.5) * sx - 0.5);
    c.cy = float((c.cy + 0.5) * sy - 0.5);
    c.width = mode.width;
    c.height = mode.height;
  }
  p.sensor.depth_scale = 1000.0;  // OpenNI2 depth in millimetres
  if (!p.sensor.device || !p.sensor.device->exposure_ms_per_unit)
    p.sensor.warnings.push_back(Say(words::kNoExposureUnit));
  if (!p.sensor.device) p.sensor.device = SensorInfo::Device{device.serial, device.name, std::nullopt};
  return p;
}

fs::path SaveProfile(const std::string& serial, SensorInfo sensor) {
  const fs::path file = ProfilePath(serial);
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw InputError(file.parent_path(), "cannot create the profile folder: " + ec.message());
  if (!sensor.device) sensor.device = SensorInfo::Device{};
  sensor.device->serial = serial;
  io::WriteSensorJson(file, sensor);
  return file;
}

}  // namespace hdrf::sensors
