// sensor.json reader and writer (docs/formats.md).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "radiometry/sensor.h"

namespace hdrf::io {

// Throws InputError naming the file (and the JSON line, for syntax errors) and the key.
SensorInfo ReadSensorJson(const std::filesystem::path& file);

void WriteSensorJson(const std::filesystem::path& file, const SensorInfo& sensor);

// The same, as a JSON value inside another file (project files): errors name `file`;
// `what` names the sensor in the writer's messages.
SensorInfo SensorFromJson(const std::filesystem::path& file, const nlohmann::json& j);
nlohmann::json SensorToJson(const SensorInfo& sensor, const std::string& what);

}  // namespace hdrf::io
