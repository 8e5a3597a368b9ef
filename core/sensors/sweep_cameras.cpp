#include "sensors/sweep_cameras.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "io/sensor_json.h"
#include "io/source_spec.h"
#include "radiometry/calibration.h"
#include "sim/sweep_camera.h"

namespace hdrf::sensors {

using namespace std::chrono_literals;

LiveSweepCamera::LiveSweepCamera(const LiveOptions& options, std::optional<double> unit_ms) {
  camera_ = OpenNiCamera::Open(options.device, options.mode);
  if (!camera_->has_camera_settings())
    throw SensorError("device '" + camera_->entry().name + "' (" + camera_->entry().uri +
                      ") has no camera settings: its exposure cannot be set, so it cannot be calibrated by a sweep");
  profile_ = ProfileFor(camera_->entry(), options.mode);
  if (unit_ms) {
    if (!(*unit_ms > 0 && *unit_ms < 100)) throw SettingError("unit", "must be a positive number of milliseconds");
    unit_ms_ = *unit_ms;
    unit_known_ = true;
  } else if (profile_.sensor.device && profile_.sensor.device->exposure_ms_per_unit) {
    unit_ms_ = *profile_.sensor.device->exposure_ms_per_unit;
    unit_known_ = true;
  }
  if (options.gain) camera_->SetGain(*options.gain);
}

std::string LiveSweepCamera::description() const {
  const DeviceEntry& e = camera_->entry();
  return e.name + (e.serial.empty() ? "" : " (" + e.serial + ")");
}

radiometry::ExposureLimits LiveSweepCamera::limits() const {
  // OpenNI2 reports no range; one raw step up to a second (or 10000 steps).
  return {unit_ms_, std::min(1000.0, 10000 * unit_ms_)};
}

int LiveSweepCamera::Raw(double ms) const {
  const radiometry::ExposureLimits lim = limits();
  return std::max(1, int(std::lround(std::clamp(ms, lim.min_ms, lim.max_ms) / unit_ms_)));
}

double LiveSweepCamera::Quantise(double ms) const { return Raw(ms) * unit_ms_; }

SensorInfo LiveSweepCamera::sensor() const {
  SensorInfo s = profile_.sensor;
  s.response.reset();
  s.noise.reset();
  s.warnings.clear();
  if (!s.device) s.device = SensorInfo::Device{};
  s.device->serial = camera_->entry().serial;
  s.device->name = camera_->entry().name;
  if (unit_known_) s.device->exposure_ms_per_unit = unit_ms_;
  return s;
}

void LiveSweepCamera::SetAutomatic(bool auto_exposure, bool auto_white_balance) {
  camera_->SetAutoWhiteBalance(auto_white_balance);
  camera_->SetAutoExposure(auto_exposure);
  camera_->Flush();
}

radiometry::ColourLock LiveSweepCamera::colour_lock() const {
  const ExposureState s = camera_->exposure();
  return {s.auto_exposure, s.auto_white_balance};
}

double LiveSweepCamera::SetExposure(double ms) {
  const int raw = Raw(ms);
  camera_->SetExposure(raw);
  camera_->Flush();
  return raw * unit_ms_;
}

ColorImage LiveSweepCamera::Grab() {
  std::optional<LiveFrame> f = camera_->Read(2000ms);
  if (!f) throw SensorError("device '" + camera_->entry().name + "' delivered no frame for 2 s");
  return std::move(f->color);
}

ColorImage LiveSweepCamera::GrabLatest() {
  camera_->Flush();
  return Grab();
}

namespace {

double Number(const std::string& key, const std::string& v) {
  std::size_t used = 0;
  double d = 0;
  try {
    d = std::stod(v, &used);
  } catch (const std::logic_error&) {
    used = 0;
  }
  if (used != v.size() || v.empty()) throw SettingError(key, "'" + v + "' is not a number");
  return d;
}

}  // namespace

std::unique_ptr<radiometry::SweepCamera> OpenSweepCamera(const std::string& spec) {
  if (spec == "synthetic" || spec.rfind("synthetic:", 0) == 0) {
    sim::SyntheticSweepOptions o;
    for (const auto& [k, v] : io::SplitSpec(spec, 10, "synthetic:response=gamma2.2")) {
      if (k == "response") {
        if (v.size() > 5 && v.substr(v.size() - 5) == ".json") {
          const SensorInfo s = io::ReadSensorJson(v);
          if (!s.response) throw InputError(v, "has no 'response' to give the synthetic sensor");
          o.response = *s.response;
          radiometry::ScaleToUnitAt128(o.response);
          if (s.noise) {  // in the file's units: rescale with the response
            const auto& raw = *s.response;
            for (int c = 0; c < 3; ++c) {
              const float scale = raw.table[c][128] > 0 ? 1.f / raw.table[c][128] : 1.f;
              o.noise.sigma_s[c] = s.noise->sigma_s[c] * std::sqrt(scale);
              o.noise.sigma_c[c] = s.noise->sigma_c[c] * scale;
            }
          }
          o.response_name = std::filesystem::path(v).filename().string();
        } else {
          o.response = sim::NamedResponse(v);
          o.response_name = v;
        }
      } else if (k == "scene") {
        o.scene = v;
      } else if (k == "size") {
        io::ParseSize(v, &o.width, &o.height);
      } else if (k == "seed") {
        o.seed = std::uint32_t(Number("seed", v));
      } else {
        throw SettingError("source", "unknown synthetic setting '" + k + "' (response, scene, size, seed)");
      }
    }
    return std::make_unique<sim::SyntheticSweepCamera>(o);
  }
  if (IsLiveSpec(spec)) {
    std::optional<double> unit;
    std::string rest = "openni:";
    for (const auto& [k, v] : io::SplitSpec(spec, 7, "openni:device=SERIAL,unit=0.1")) {
      if (k == "unit") unit = Number("unit", v);
      else if (k == "device" || k == "mode" || k == "gain") rest += k + "=" + v + ",";
      else throw SettingError("source", "unknown setting '" + k + "' for a sweep camera (device, mode, unit, gain)");
    }
    return std::make_unique<LiveSweepCamera>(ParseLiveSpec(rest), unit);
  }
  throw SettingError("source", "'" + spec + "' is not a sweep camera: use synthetic[:response=...] or openni:[device=...]");
}

}  // namespace hdrf::sensors
