#include "sim/sweep_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/error.h"
#include "radiometry/calibration.h"
#include "sim/builtin_sensor.h"
#include "sim/noise.h"
#include "sim/sweep_simulator.h"
#include "sim/synthetic_source.h"

namespace hdrf::sim {

SyntheticSweepOptions::SyntheticSweepOptions()
    : response(*BuiltinXtionProfile().response), noise(kSweepNoise) {}

void SyntheticSweepOptions::Check() const {
  if (scene != "room" && scene != "desk") throw SettingError("scene", "is '" + scene + "'; use room or desk");
  if (width < 32 || height < 24 || width > 4096 || height > 4096)
    throw SettingError("size", "must be between 32x24 and 4096x4096");
  if (!(limits.min_ms > 0) || !(limits.max_ms > limits.min_ms))
    throw SettingError("exposure limits", "need 0 < min < max");
  if (!(flicker >= 0 && flicker < 1)) throw SettingError("flicker", "must be in [0, 1)");
  response.Check("synthetic sensor response");
  noise.Check("synthetic sensor noise");
}

radiometry::InverseResponse NamedResponse(const std::string& name) {
  if (name == "xtion") return *BuiltinXtionProfile().response;
  if (name == "srgb") return radiometry::InverseResponse::Srgb();
  radiometry::InverseResponse r;
  double gamma = 1.0;
  if (name.rfind("gamma", 0) == 0) {
    char* end = nullptr;
    const std::string v = name.substr(5);
    gamma = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !(gamma >= 0.2 && gamma <= 5))
      throw SettingError("response", "'" + name + "': gamma needs a number from 0.2 to 5 (gamma2.2)");
  } else if (name != "linear") {
    throw SettingError("response", "'" + name + "' is not a response; use xtion, srgb, linear, gammaG (gamma2.2) "
                                                 "or a sensor.json file");
  }
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < radiometry::kLevels; ++i) r.table[c][i] = float(std::pow(i / 255.0, gamma));
  return r;
}

SyntheticSweepCamera::SyntheticSweepCamera(SyntheticSweepOptions options) : o_(std::move(options)) {
  o_.Check();
  radiometry::ScaleToUnitAt128(o_.response);
  SimOptions s;
  s.scene = o_.scene;
  s.seed = o_.seed;
  s.width = o_.width;
  s.height = o_.height;
  s.sweep = true;
  s.sweep_exposures_ms = {1.0, 2.0};  // (the source needs two; only the view is used)
  s.sweep_repeats = 1;
  s.response = o_.response;
  s.noise = o_.noise;
  auto source = std::make_shared<SyntheticSource>(s);
  radiance_ = source->RenderView(0).radiance;
  source_ = std::move(source);
}

std::string SyntheticSweepCamera::description() const {
  return "Synthetic sensor (" + o_.scene + " scene, " + o_.response_name + " response, " +
         std::to_string(o_.width) + "x" + std::to_string(o_.height) + ")";
}

void SyntheticSweepCamera::SetAutomatic(bool auto_exposure, bool auto_white_balance) {
  lock_ = {auto_exposure, auto_white_balance};
}

void SyntheticSweepCamera::KnockAside(int px) {
  RadianceImage shifted(o_.width, o_.height);
  for (int y = 0; y < o_.height; ++y)
    for (int x = 0; x < o_.width; ++x) shifted(x, y) = radiance_(std::clamp(x + px, 0, o_.width - 1), y);
  radiance_ = std::move(shifted);
}

double SyntheticSweepCamera::Quantise(double ms) const {
  // A 10 us exposure unit, as many sensors count in lines of about that length.
  return std::clamp(std::round(ms * 100.0) / 100.0, o_.limits.min_ms, o_.limits.max_ms);
}

SensorInfo SyntheticSweepCamera::sensor() const {
  SensorInfo s;
  s.camera = SimCamera(o_.width, o_.height);
  s.device = SensorInfo::Device{serial(), description(), 1.0};
  return s;
}

double SyntheticSweepCamera::SetExposure(double ms) {
  exposure_ms_ = Quantise(ms);
  return exposure_ms_;
}

ColorImage SyntheticSweepCamera::Grab() {
  const int n = grabs_++;
  const RadianceImage& L = radiance_;
  double t = exposure_ms_;
  if (lock_.auto_exposure) t = std::clamp(0.5 / std::max(MeterCentre(L), 1e-6), o_.limits.min_ms, o_.limits.max_ms);
  if (o_.flicker > 0) t *= 1.0 + o_.flicker * ((n % 2) ? 1.0 : -1.0);
  return source_->Expose(L, t, Hash(o_.seed + 7u, std::uint32_t(n)));
}

}  // namespace hdrf::sim
