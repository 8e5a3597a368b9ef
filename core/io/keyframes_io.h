// A scan's keyframes on disk (docs/formats.md): keyframes/NNNNNN.png (the colour as the
// sensor delivered it), keyframes.json (camera, PCF power, per keyframe: frame index,
// timestamp, pose, exposure ratio, file) and sensor.json (the response the radiance comes
// from), in the scan's output folder.
#pragma once

#include <filesystem>
#include <vector>

#include "pipeline/keyframes.h"
#include "radiometry/sensor.h"

namespace hdrf::io {

struct KeyframeSet {
  std::vector<pipeline::Keyframe> keyframes;
  SensorInfo sensor;
  int pcf_power = 1;
};

void WriteKeyframes(const std::filesystem::path& scan_dir, const std::vector<pipeline::Keyframe>& keyframes,
                    const SensorInfo& sensor, int pcf_power);
// Throws InputError naming the file on anything missing or malformed.
KeyframeSet ReadKeyframes(const std::filesystem::path& scan_dir);
bool HasKeyframes(const std::filesystem::path& scan_dir);

}  // namespace hdrf::io
