// OpenEXR images of linear RGB radiance.
#pragma once

#include <filesystem>

#include "common/image.h"

namespace hdrf::io {

enum class ExrPrecision { kHalf, kFloat };

// Reads channels R, G, B (or Y, replicated) into floats. Throws InputError naming the file
// when it is missing, not OpenEXR, lacks the channels, or holds NaN/infinite pixels.
RadianceImage ReadExr(const std::filesystem::path& file);

// Writes R, G, B (ZIP compression) through a temporary file and a rename.
void WriteExr(const std::filesystem::path& file, const RadianceImage& image,
              ExrPrecision precision = ExrPrecision::kHalf);

}  // namespace hdrf::io
