// Exposure sweeps (docs/formats.md): a recorded sequence of a static scene whose every colour
// frame has an exposure in exposure.txt. Depth is optional.
#pragma once

#include <filesystem>

#include "radiometry/calibration.h"

namespace hdrf::io {

// Throws InputError naming exposure.txt when it is missing or a frame has no exposure.
radiometry::Sweep ReadSweep(const std::filesystem::path& folder);

}  // namespace hdrf::io
