// Auto exposure: how the simulated camera picks each frame's exposure time.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace hdrf::sim {

enum class AeMode {
  kFixed,    // one exposure for every frame
  kSmooth,   // exposure = C / mean radiance of a central patch, one frame late, damped
  kFlicker,  // drawn from {3, 6, 12, 24, 48, 96} ms each frame, never twice in a row
  kList,     // an explicit list, repeated
};

struct AeOptions {
  AeMode mode = AeMode::kSmooth;
  double fixed_ms = 10.0;                 // kFixed, and the first frame of kSmooth
  double target = 0.6;                    // kSmooth: wanted mean R of the central patch
  double damping = 0.35;                  // kSmooth: share of the log-error corrected per frame
  double min_ms = 0.5, max_ms = 100.0;    // kSmooth: the exposure range of the camera
  std::vector<double> flicker_ms = {3, 6, 12, 24, 48, 96};
  std::vector<double> list_ms;            // kList
  void Check() const;                     // throws SettingError naming --ae / --exposures
};

AeMode ParseAeMode(const std::string& s);  // "fixed", "smooth", "flicker", "list"
const char* AeModeName(AeMode m);

class AutoExposure {
 public:
  AutoExposure(AeOptions options, std::uint32_t seed);
  // Exposure of frame i. For kSmooth, `metered_radiance` is the mean scene radiance of the
  // central patch of the previous frame (< 0 for the first frame).
  double Next(int i, double metered_radiance);

 private:
  AeOptions o_;
  std::uint32_t seed_;
  double current_ms_;
  int last_flicker_ = -1;
};

}  // namespace hdrf::sim
