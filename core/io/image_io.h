// PNG colour and 16-bit depth images, checked against what docs/formats.md promises.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "common/image.h"

namespace hdrf::io {

// Called with an image's width and height from its header, before it is decoded (and again
// after, for formats whose header is not read): throws to refuse the image.
using HeaderCheck = std::function<void(int width, int height)>;

// The check every frame reader makes: the image is `width` x `height`, the camera's size in
// sensor.json ("image is WxH but sensor.json says WxH", naming `file`).
HeaderCheck ExpectSize(const std::filesystem::path& file, int width, int height);

// 8-bit, 3-channel colour (an alpha channel is dropped). Throws InputError naming the file
// when it is missing, not a regular file, larger than common/input_file.h allows (bytes, or
// pixels from its header, or more than the free memory holds), unreadable, or has the wrong
// bit depth or channel count.
ColorImage ReadColorImage(const std::filesystem::path& file, const HeaderCheck& check_header = {});

// 16-bit, 1-channel depth in sensor units. Same checks as above.
DepthRawImage ReadDepthImage(const std::filesystem::path& file, const HeaderCheck& check_header = {});

// Lossless PNG writers (through an exclusive staging file and a rename: io/output_file.h).
void WriteColorPng(const std::filesystem::path& file, const ColorImage& image);
void WriteDepthPng(const std::filesystem::path& file, const DepthRawImage& image);
// The PNG bytes of a colour image (for containers such as glTF binaries).
std::vector<std::uint8_t> EncodeColorPng(const ColorImage& image);
// The reverse, from bytes held inside `file` (project files); throws InputError naming the
// file and `what` where the bytes are no 8-bit RGB image.
ColorImage DecodeColorPng(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes,
                          const std::string& what);

// Raw depth to metres (0 stays 0 = no data).
// Raw depth codes to metres; 0 and kDepthInvalidMax are both "no depth" (0 m).
inline constexpr std::uint16_t kDepthInvalidMax = 65535;
DepthImage DepthToMetres(const DepthRawImage& raw, double scale);
DepthRawImage DepthFromMetres(const DepthImage& depth_m, double scale);

}  // namespace hdrf::io
