// What a sequence says about its sensor (FORMATS.md, sensor.json).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common/camera.h"
#include "radiometry/response.h"

namespace hdrf {

struct SensorInfo {
  PinholeCamera camera;                                // colour camera; depth registered to it
  double depth_scale = 5000.0;                         // raw depth units per metre
  std::optional<radiometry::InverseResponse> response;  // f^-1 per channel, if calibrated
  std::optional<radiometry::NoiseModel> noise;          // sigma_s, sigma_c, if calibrated
  // Written by `hdrfusion simulate` ("synthetic": {"scene", "seed"}): lets `eval` rebuild
  // the scene to measure geometry and radiance. Other tools ignore it (FORMATS.md).
  struct Synthetic {
    std::string scene;
    std::uint32_t seed = 1;
  };
  std::optional<Synthetic> synthetic;
};

}  // namespace hdrf
