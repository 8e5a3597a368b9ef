// OpenEXR images of linear RGB radiance.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/image.h"

namespace hdrf::io {

enum class ExrPrecision { kHalf, kFloat };

// Reads channels R, G, B (or Y, replicated) into floats. Throws InputError naming the file
// when it is missing, not OpenEXR, lacks the channels, or holds NaN/infinite pixels.
RadianceImage ReadExr(const std::filesystem::path& file);

// Writes R, G, B (ZIP compression) through a temporary file and a rename.
void WriteExr(const std::filesystem::path& file, const RadianceImage& image,
              ExrPrecision precision = ExrPrecision::kHalf);

// More channels beside R, G, B (alpha "A", depth "Z", ...) and string attributes in the header.
struct ExrChannel {
  std::string name;
  const Image<float>* image = nullptr;  // the size of the RGB image
  ExrPrecision precision = ExrPrecision::kFloat;
};
struct ExrWriteOptions {
  ExrPrecision precision = ExrPrecision::kHalf;  // of R, G, B
  std::vector<ExrChannel> extra;
  std::vector<std::pair<std::string, std::string>> attributes;
};
void WriteExr(const std::filesystem::path& file, const RadianceImage& image, const ExrWriteOptions& o);

// One channel as floats; throws InputError naming the file when it is missing.
Image<float> ReadExrChannel(const std::filesystem::path& file, const std::string& name);
// A string attribute of the header, if there is one.
std::optional<std::string> ReadExrAttribute(const std::filesystem::path& file, const std::string& name);

}  // namespace hdrf::io
