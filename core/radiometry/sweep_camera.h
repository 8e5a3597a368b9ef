// A camera an exposure sweep is captured from (the calibration wizard and
// `hdrfusion capture-sweep`): the synthetic sensor (sim/sweep_camera.h) or a live OpenNI2
// device (sensors/live_sweep_camera.h). It only sets an exposure and hands out frames; the
// plan, the checks and the writing are in io/sweep_capture.h.
#pragma once

#include <string>

#include "common/image.h"
#include "radiometry/sensor.h"

namespace hdrf::radiometry {

struct ExposureLimits {
  double min_ms = 0.1, max_ms = 1000.0;
};

// What the camera reports of its automatic colour controls.
struct ColourLock {
  bool auto_exposure = false, auto_white_balance = false;
};

class SweepCamera {
 public:
  virtual ~SweepCamera() = default;
  // Named in messages ("Synthetic sensor (room, gamma 2.2)", "PrimeSense Carmine 1.09 (1406120314)").
  virtual std::string description() const = 0;
  // The device's serial (the profile the calibration is stored under); "" for none.
  virtual std::string serial() const = 0;
  virtual ExposureLimits limits() const = 0;
  // The exposure the camera would really use for `ms` (its unit, its limits).
  virtual double Quantise(double ms) const = 0;
  // What the sweep's sensor.json says: camera intrinsics, depth scale and the device block;
  // never a response or noise (that is what the sweep is for).
  virtual SensorInfo sensor() const = 0;
  // Switches auto exposure and auto white balance on or off; throws hdrf::Error when the
  // camera has no such control or does not take the value.
  virtual void SetAutomatic(bool auto_exposure, bool auto_white_balance) = 0;
  // As the camera reports it now (read back, not remembered).
  virtual ColourLock colour_lock() const = 0;
  // Sets the exposure and returns the one in force (rounded to the device's unit); frames
  // from the next Grab on are taken at it.
  virtual double SetExposure(double ms) = 0;
  // The next frame (throws hdrf::Error when the camera stops delivering).
  virtual ColorImage Grab() = 0;
  // A frame taken now, not one waiting in a queue (a live preview).
  virtual ColorImage GrabLatest() { return Grab(); }
};

}  // namespace hdrf::radiometry
