// What a sequence says about its sensor (FORMATS.md, sensor.json).
#pragma once

#include <optional>

#include "common/camera.h"
#include "radiometry/response.h"

namespace hdrf {

struct SensorInfo {
  PinholeCamera camera;                                // colour camera; depth registered to it
  double depth_scale = 5000.0;                         // raw depth units per metre
  std::optional<radiometry::InverseResponse> response;  // f^-1 per channel, if calibrated
  std::optional<radiometry::NoiseModel> noise;          // sigma_s, sigma_c, if calibrated
};

}  // namespace hdrf
