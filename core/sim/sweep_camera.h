// The synthetic sensor as a sweep camera: a static camera looking at a built-in scene
// through a chosen response and noise, for demos and tests of the calibration wizard that
// need no hardware. Its truth (response, noise) is known, so a calibration can be scored.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "radiometry/response.h"
#include "radiometry/sweep_camera.h"

namespace hdrf::sim {

struct SyntheticSweepOptions {
  std::string scene = "room";  // built-in scene: room, desk, hall
  std::uint32_t seed = 1;      // textures, lights and noise
  int width = 320, height = 240;
  radiometry::InverseResponse response;  // the truth; scaled to f^-1(128) = 1 when used
  radiometry::NoiseModel noise;          // in the units of that scaled response
  std::string response_name = "xtion";   // named in description()
  radiometry::ExposureLimits limits{0.05, 2000.0};
  // Frames whose mean brightness flickers by this share (0: steady light): a fault the
  // capture checks must catch (KnockAside is the other).
  double flicker = 0;

  SyntheticSweepOptions();  // the built-in Xtion response and the sweep noise of the tests
  void Check() const;       // throws SettingError naming the key
};

// A response by name: "xtion" (the built-in profile's), "srgb", "gammaG" (f^-1(I) = (I/255)^G,
// e.g. gamma2.2), "linear". Throws SettingError for another name.
radiometry::InverseResponse NamedResponse(const std::string& name);

class SyntheticSweepCamera : public radiometry::SweepCamera {
 public:
  explicit SyntheticSweepCamera(SyntheticSweepOptions options);
  std::string description() const override;
  std::string serial() const override { return "HDRF-SYNTHETIC"; }
  radiometry::ExposureLimits limits() const override { return o_.limits; }
  double Quantise(double ms) const override;
  SensorInfo sensor() const override;
  void SetAutomatic(bool auto_exposure, bool auto_white_balance) override;
  radiometry::ColourLock colour_lock() const override { return lock_; }
  double SetExposure(double ms) override;
  ColorImage Grab() override;

  const SyntheticSweepOptions& options() const { return o_; }
  // The truth, as a calibration of this camera should find it (f^-1(128) = 1).
  const radiometry::InverseResponse& true_response() const { return o_.response; }
  // The camera knocked aside: from the next grab on the view is shifted by `px` pixels.
  void KnockAside(int px);

 private:
  SyntheticSweepOptions o_;
  RadianceImage radiance_;
  double exposure_ms_ = 10;
  radiometry::ColourLock lock_{true, true};  // as cameras start: automatic
  int grabs_ = 0;
  std::shared_ptr<const class SyntheticSource> source_;
};

}  // namespace hdrf::sim
