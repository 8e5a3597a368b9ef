// What a sequence says about its sensor (sensor.json, docs/formats.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/camera.h"
#include "radiometry/response.h"

namespace hdrf {

struct SensorInfo {
  PinholeCamera camera;                                // colour camera; depth registered to it
  double depth_scale = 5000.0;                         // raw depth units per metre
  std::optional<radiometry::InverseResponse> response;  // f^-1 per channel, if calibrated
  std::optional<radiometry::NoiseModel> noise;          // sigma_s, sigma_c, if calibrated
  // Written by `hdrfusion simulate` ("hdrfusion": {"synthetic": {"scene", "seed"}}): lets
  // `eval` rebuild the scene to measure geometry and radiance (docs/formats.md).
  struct Synthetic {
    std::string scene;
    std::uint32_t seed = 1;
  };
  std::optional<Synthetic> synthetic;
  // What the reader ignored and the user should know (a block of another tool under a name
  // the project also uses), one line each, naming the file.
  std::vector<std::string> warnings;
};

}  // namespace hdrf
