// A whole calibration from a sweep, as `hdrfusion calibrate` and the calibration wizard's
// Fit and Validate pages run it: the checks on the sweep, the response fit, the noise level
// function, the PCF, and the verdict. One object; the CLI calls Run, the wizard runs it on
// a worker thread.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include "radiometry/calibration.h"
#include "radiometry/pcf.h"
#include "radiometry/sensor.h"
#include "radiometry/validation.h"

namespace hdrf::radiometry {

struct CalibrationSettings {
  // "debevec" (the default: the most accurate of the three on the 201 DoRF curves, 0.57 %
  // of the range at worst), "robertson", or "emor" (needs the basis).
  std::string method = "debevec";
  std::optional<EmorBasis> basis;  // for emor
  int emor_components = EmorOptions{}.components;
  int threshold_passes = DebevecOptions{}.threshold_passes;
  void Check() const;  // throws SettingError naming the key
};

struct CalibrationOutcome {
  ResponseFit fit;
  std::optional<NoiseFit> noise_fit;  // absent when it could not be fitted (noise_error says why)
  std::string noise_error;
  NoiseModel noise;                   // the fitted noise, or a generic one for the merge checks
  PcfTables pcf;
  CalibrationCheck check;
  // The response always (unless redo); the noise only when fitted and fitting well.
  bool noise_saved() const { return noise_fit.has_value() && check.noise_usable; }
  // `base` (camera, device) with this calibration's response and, if saved, noise.
  SensorInfo Apply(SensorInfo base) const;
};

// Stages reported: "checking the sweep", "fitting the response", "fitting the noise",
// "validating" (fraction 0..1 of the whole).
using CalibrationProgress = std::function<void(const std::string& stage, double fraction)>;

// Throws hdrf::Error (naming the sweep) when the sweep cannot be calibrated
// (CheckSweepForCalibration), and when cancelled (between stages).
CalibrationOutcome RunCalibration(const Sweep& sweep, const CalibrationSettings& settings,
                                  const CalibrationProgress& progress = {},
                                  const std::atomic<bool>* cancel = nullptr);

}  // namespace hdrf::radiometry
