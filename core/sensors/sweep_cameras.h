// The cameras a calibration sweep is captured from, by spec (docs/calibration_wizard.md):
//   synthetic[:response=NAME|FILE.json][,scene=room|desk|hall][,size=WxH][,seed=N]
//       the synthetic sensor through a chosen response (xtion, srgb, linear, gammaG, or the
//       response and noise of a sensor.json), so that demos and tests need no hardware
//   openni:[device=URI|SERIAL][,mode=vga|qvga][,unit=MS][,gain=N]
//       a live OpenNI2 camera; `unit` is its exposure step in milliseconds when the
//       device's profile gives none
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "radiometry/sweep_camera.h"
#include "sensors/live_source.h"

namespace hdrf::sensors {

class LiveSweepCamera : public radiometry::SweepCamera {
 public:
  // Opens the device (its automatic controls left as they are) and its profile. Without an
  // exposure unit (profile or `unit_ms`) exposures are in the device's raw unit, which is
  // assumed linear in time (the sweep then records raw units; the response is the same).
  LiveSweepCamera(const LiveOptions& options, std::optional<double> unit_ms);
  std::string description() const override;
  std::string serial() const override { return camera_->entry().serial; }
  radiometry::ExposureLimits limits() const override;
  double Quantise(double ms) const override;
  SensorInfo sensor() const override;
  void SetAutomatic(bool auto_exposure, bool auto_white_balance) override;
  radiometry::ColourLock colour_lock() const override;
  double SetExposure(double ms) override;
  ColorImage Grab() override;
  ColorImage GrabLatest() override;  // drops the queued frames first

  // False when exposures are in the device's raw unit (no unit known).
  bool exposure_in_ms() const { return unit_known_; }
  const Profile& profile() const { return profile_; }

 private:
  int Raw(double ms) const;
  std::unique_ptr<OpenNiCamera> camera_;
  Profile profile_;
  double unit_ms_ = 1.0;
  bool unit_known_ = false;
};

// A camera for a spec above; throws SettingError naming the key, SensorError for a device
// that cannot be opened, InputError for a response file that cannot be read.
std::unique_ptr<radiometry::SweepCamera> OpenSweepCamera(const std::string& spec);

}  // namespace hdrf::sensors
