// sensor.json reader and writer (docs/formats.md).
#pragma once

#include <filesystem>

#include "radiometry/sensor.h"

namespace hdrf::io {

// Throws InputError naming the file (and the JSON line, for syntax errors) and the key.
SensorInfo ReadSensorJson(const std::filesystem::path& file);

void WriteSensorJson(const std::filesystem::path& file, const SensorInfo& sensor);

}  // namespace hdrf::io
