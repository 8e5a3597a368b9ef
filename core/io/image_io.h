// PNG colour and 16-bit depth images, checked against what docs/formats.md promises.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "common/image.h"

namespace hdrf::io {

// 8-bit, 3-channel colour (an alpha channel is dropped). Throws InputError naming the file
// when it is missing, unreadable, or has the wrong bit depth or channel count.
ColorImage ReadColorImage(const std::filesystem::path& file);

// 16-bit, 1-channel depth in sensor units. Same checks as above.
DepthRawImage ReadDepthImage(const std::filesystem::path& file);

// Lossless PNG writers (through a temporary file and a rename).
void WriteColorPng(const std::filesystem::path& file, const ColorImage& image);
void WriteDepthPng(const std::filesystem::path& file, const DepthRawImage& image);
// The PNG bytes of a colour image (for containers such as glTF binaries).
std::vector<std::uint8_t> EncodeColorPng(const ColorImage& image);
// The reverse, from bytes held inside `file` (project files); throws InputError naming the
// file and `what` where the bytes are no 8-bit RGB image.
ColorImage DecodeColorPng(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes,
                          const std::string& what);

// Raw depth to metres (0 stays 0 = no data).
DepthImage DepthToMetres(const DepthRawImage& raw, double scale);
DepthRawImage DepthFromMetres(const DepthImage& depth_m, double scale);

}  // namespace hdrf::io
