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
  // A live camera's profile ("hdrfusion": {"device": {...}}): the device it was measured
  // on, and how its raw exposure unit maps to milliseconds (OpenNI2 reports exposure in a
  // device unit; without the mapping, exposures set by hand cannot be recorded as times).
  struct Device {
    std::string serial;
    std::string name;
    std::optional<double> exposure_ms_per_unit;
  };
  std::optional<Device> device;
  // What the reader ignored and the user should know (a block of another tool under a name
  // the project also uses), one line each, naming the file.
  std::vector<std::string> warnings;
};

}  // namespace hdrf
