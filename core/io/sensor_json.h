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
// The same, keeping what an existing `file` holds beyond what this project writes (other
// tools' keys, and keys of its own "hdrfusion" block the sensor does not set): a calibration
// written over a recording's sensor.json completes it instead of dropping the rest. Where
// `file` is absent or not a JSON object, it is written as WriteSensorJson does.
void UpdateSensorJson(const std::filesystem::path& file, const SensorInfo& sensor);

// The same, as a JSON value inside another file (project files): errors name `file`;
// `what` names the sensor in the writer's messages.
SensorInfo SensorFromJson(const std::filesystem::path& file, const nlohmann::json& j);
nlohmann::json SensorToJson(const SensorInfo& sensor, const std::string& what);

}  // namespace hdrf::io
