// How input files are opened: only regular files, of a size that makes sense for what they
// are, and images only when their header's dimensions can be held. A FIFO named in a list
// would block the reader forever, /dev/zero never ends, a 100 MB sensor.json is not a sensor
// description, and a 700 KB PNG can claim 30000x30000 pixels.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace hdrf {

inline constexpr std::uintmax_t kMiB = std::uintmax_t(1) << 20;
inline constexpr std::uintmax_t kMaxTextBytes = 64 * kMiB;      // JSON, lists, tables, trajectories
inline constexpr std::uintmax_t kMaxImageBytes = 1024 * kMiB;   // one encoded image
#ifndef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 28;  // 268 Mpx (16384 x 16384)
#else
// Fuzzing builds (tools/fuzz.sh) stop at 4 Mpx: a few kilobytes of compressed OpenEXR can
// legally describe hundreds of megapixels, and clearing that memory would take the fuzzer's
// time from the parsers.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 22;
#endif
inline constexpr int kMaxImageSide = 1 << 16;

// Throws InputError naming the file unless it is a regular file (links followed) of at most
// max_bytes; `what` says what the file is ("a settings file"). Returns its size. Opens
// without blocking, so a FIFO is refused rather than waited on.
std::uintmax_t CheckInputFile(const std::filesystem::path& file, std::uintmax_t max_bytes, const char* what);

// The whole file, after the same checks, read through the one descriptor that was checked.
std::string ReadInputFile(const std::filesystem::path& file, std::uintmax_t max_bytes, const char* what);

// Dimensions and bytes per pixel (all channels, decoded) from an image's header: PNG, JPEG
// and TIFF are read, others give nullopt (and are not read: the readers decode only what
// they can size first). Throws InputError for a header that is not one.
struct ImageHeader {
  int width = 0, height = 0;
  int bytes_per_pixel = 0;
};
std::optional<ImageHeader> PeekImageHeader(const std::filesystem::path& file, const std::string& bytes);

// Throws InputError naming the file if an image of w x h pixels (bytes_per_pixel decoded)
// is more than this program reads, or more than the machine's free memory can hold.
void CheckImageDimensions(const std::filesystem::path& file, long long w, long long h, int bytes_per_pixel);

}  // namespace hdrf
