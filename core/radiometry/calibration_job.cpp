#include "radiometry/calibration_job.h"

#include "common/error.h"

namespace hdrf::radiometry {

void CalibrationSettings::Check() const {
  if (method != "debevec" && method != "robertson" && method != "emor")
    throw SettingError("method", "'" + method + "' is not a method; use debevec, robertson or emor");
  if (method == "emor" && !basis) throw SettingError("emor-basis", "the EMoR method needs its basis (invemor.txt)");
  if (emor_components < 1 || emor_components > 25) throw SettingError("emor-components", "must be 1 to 25");
  if (threshold_passes < 0 || threshold_passes > 10) throw SettingError("threshold-passes", "must be 0 to 10");
}

SensorInfo CalibrationOutcome::Apply(SensorInfo base) const {
  base.response = fit.inverse;
  if (noise_saved())
    base.noise = noise;
  else
    base.noise.reset();
  base.warnings.clear();
  return base;
}

CalibrationOutcome RunCalibration(const Sweep& sweep, const CalibrationSettings& settings,
                                  const CalibrationProgress& progress, const std::atomic<bool>* cancel) {
  settings.Check();
  auto report = [&](const char* stage, double f) {
    if (cancel && cancel->load()) throw Error(sweep.source + ": calibration cancelled");
    if (progress) progress(stage, f);
  };
  report("checking the sweep", 0.0);
  CheckSweepForCalibration(sweep);
  auto fit_sweep = [&](const Sweep& s) {
    if (settings.method == "debevec") {
      DebevecOptions o;
      o.threshold_passes = settings.threshold_passes;
      return FitDebevec(s, o);
    }
    if (settings.method == "robertson") {
      RobertsonOptions o;
      o.threshold_passes = settings.threshold_passes;
      return FitRobertson(s, o);
    }
    EmorOptions o;
    o.components = settings.emor_components;
    o.threshold_passes = settings.threshold_passes;
    return FitEmor(s, *settings.basis, o);
  };
  CalibrationOutcome out;
  report("fitting the response", 0.1);
  out.fit = fit_sweep(sweep);
  report("fitting the noise", 0.35);
  std::optional<std::array<double, 3>> misfit;
  try {
    out.noise_fit = FitNoise(sweep, out.fit.inverse);
    out.noise = out.noise_fit->noise;
    misfit = out.noise_fit->rms_relative_residual;
  } catch (const Error& e) {
    out.noise_error = e.what();
    out.noise.sigma_s = {0.02f, 0.02f, 0.02f};  // for the merge checks only
    out.noise.sigma_c = {0.002f, 0.002f, 0.002f};
  }
  report("validating", 0.55);
  out.check = CheckCalibration(sweep, out.fit.inverse, out.noise, misfit, [&](const Sweep& s) {
    report("validating (fitting without the held-back exposure)", 0.7);
    return fit_sweep(s).inverse;
  });
  out.pcf = ComputePcf(out.fit.inverse, out.noise);
  report("done", 1.0);
  return out;
}

}  // namespace hdrf::radiometry
