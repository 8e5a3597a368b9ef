#include "common/input_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"
#include "common/host_memory.h"

namespace hdrf {

namespace fs = std::filesystem;

namespace {

std::string Mib(std::uintmax_t bytes) {
  return std::to_string((bytes + kMiB - 1) / kMiB) + " MiB";
}

// Opens `file` for reading without blocking (a FIFO opens at once and is then refused) and
// checks what it is. Returns the descriptor (blocking again) and its size.
int OpenChecked(const fs::path& file, std::uintmax_t max_bytes, const char* what, std::uintmax_t* size) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int err = errno;
    std::error_code ec;
    if (err == ENOENT && !fs::is_symlink(file, ec)) throw InputError(file, "file is missing");
    throw InputError(file, std::string("cannot be opened for reading (") + std::strerror(err) + ")");
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const bool dir = S_ISDIR(st.st_mode);
    ::close(fd);
    throw InputError(file, dir ? std::string("is a folder, not ") + what
                               : std::string("is not a regular file (a device, pipe or socket), so it cannot be ") +
                                     what);
  }
  if (std::uintmax_t(st.st_size) > max_bytes) {
    ::close(fd);
    throw InputError(file, "is " + Mib(std::uintmax_t(st.st_size)) + ", more than the " + Mib(max_bytes) +
                               " that " + what + " may have");
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  *size = std::uintmax_t(st.st_size);
  return fd;
}

std::uint32_t BigEndian32(const std::string& b, std::size_t at) {
  return std::uint32_t(std::uint8_t(b[at])) << 24 | std::uint32_t(std::uint8_t(b[at + 1])) << 16 |
         std::uint32_t(std::uint8_t(b[at + 2])) << 8 | std::uint32_t(std::uint8_t(b[at + 3]));
}

}  // namespace

std::uintmax_t CheckInputFile(const fs::path& file, std::uintmax_t max_bytes, const char* what) {
  std::uintmax_t size = 0;
  ::close(OpenChecked(file, max_bytes, what, &size));
  return size;
}

std::string ReadInputFile(const fs::path& file, std::uintmax_t max_bytes, const char* what) {
  std::uintmax_t size = 0;
  const int fd = OpenChecked(file, max_bytes, what, &size);
  std::string bytes(std::size_t(size), '\0');
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += std::size_t(n);
  }
  const int err = errno;
  ::close(fd);
  if (got != bytes.size())
    throw InputError(file, std::string("could not be read to its end (") + (got < bytes.size() && err ? std::strerror(err) : "it shrank while read") + ")");
  return bytes;
}

std::optional<ImageHeader> PeekImageHeader(const fs::path& file, const std::string& b) {
  static const char kPng[] = "\x89PNG\r\n\x1a\n";
  if (b.size() >= 8 && b.compare(0, 8, kPng, 8) == 0) {
    // The IHDR chunk comes first: length 13, "IHDR", width, height, bit depth, colour type.
    if (b.size() < 26 || b.compare(12, 4, "IHDR") != 0) throw InputError(file, "cannot be decoded as an image: a PNG file without its header (IHDR)");
    ImageHeader h;
    const std::uint32_t w = BigEndian32(b, 16), hh = BigEndian32(b, 20);
    if (w == 0 || hh == 0 || w > 0x7fffffffu || hh > 0x7fffffffu)
      throw InputError(file, "is a PNG file whose header gives an impossible size " + std::to_string(w) + "x" +
                                 std::to_string(hh));
    const int depth = std::uint8_t(b[24]), type = std::uint8_t(b[25]);
    const int channels = type == 0 ? 1 : type == 2 ? 3 : type == 3 ? 3 : type == 4 ? 2 : type == 6 ? 4 : 4;
    h.width = int(std::min<std::uint32_t>(w, 0x7fffffff));
    h.height = int(std::min<std::uint32_t>(hh, 0x7fffffff));
    h.bytes_per_pixel = channels * (depth > 8 ? 2 : 1);
    return h;
  }
  if (b.size() >= 3 && std::uint8_t(b[0]) == 0xff && std::uint8_t(b[1]) == 0xd8) {
    // JPEG: walk the markers to the first start-of-frame (SOF0..SOF15 but DHT, JPG, DAC).
    std::size_t at = 2;
    while (at + 9 < b.size()) {
      if (std::uint8_t(b[at]) != 0xff) break;
      const int marker = std::uint8_t(b[at + 1]);
      if (marker == 0xff) {
        ++at;
        continue;
      }
      const std::size_t len = std::size_t(std::uint8_t(b[at + 2])) << 8 | std::uint8_t(b[at + 3]);
      if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
        ImageHeader h;
        h.height = std::uint8_t(b[at + 5]) << 8 | std::uint8_t(b[at + 6]);
        h.width = std::uint8_t(b[at + 7]) << 8 | std::uint8_t(b[at + 8]);
        h.bytes_per_pixel = std::max(1, int(std::uint8_t(b[at + 9])));
        return h;
      }
      if (len < 2) break;
      at += 2 + len;
    }
    return std::nullopt;  // no frame header found: the decoder will say what is wrong
  }
  if (b.size() >= 8 && (b.compare(0, 4, "II*\0", 4) == 0 || b.compare(0, 4, "MM\0*", 4) == 0)) {
    // TIFF: the first image file directory's width, length, bits and samples per pixel.
    const bool little = b[0] == 'I';
    const auto u16 = [&](std::size_t at) -> std::uint32_t {
      if (at + 2 > b.size()) throw InputError(file, "is a TIFF file cut short in its header");
      const auto x = std::uint8_t(b[at]), y = std::uint8_t(b[at + 1]);
      return little ? std::uint32_t(x) | std::uint32_t(y) << 8 : std::uint32_t(x) << 8 | y;
    };
    const auto u32 = [&](std::size_t at) -> std::uint32_t {
      return little ? u16(at) | u16(at + 2) << 16 : u16(at) << 16 | u16(at + 2);
    };
    const std::size_t ifd = u32(4);
    const std::uint32_t entries = u16(ifd);
    std::uint32_t w = 0, h = 0, bits = 8, samples = 1;
    for (std::uint32_t e = 0; e < entries; ++e) {
      const std::size_t at = ifd + 2 + 12 * std::size_t(e);
      const std::uint32_t tag = u16(at), type = u16(at + 2), count = u32(at + 4);
      // A SHORT value sits in the first half of the value field; a LONG fills it.
      const auto value = [&] { return type == 3 ? u16(at + 8) : u32(at + 8); };
      if (tag == 256) w = value();
      else if (tag == 257) h = value();
      else if (tag == 277) samples = value();
      else if (tag == 258) bits = count <= (type == 3 ? 2u : 1u) ? value() : u16(u32(at + 8));
    }
    if (w == 0 || h == 0 || w > 0x7fffffffu || h > 0x7fffffffu)
      throw InputError(file, "is a TIFF file whose header gives no usable size (" + std::to_string(w) + "x" +
                                 std::to_string(h) + ")");
    ImageHeader hd;
    hd.width = int(w);
    hd.height = int(h);
    hd.bytes_per_pixel = int(std::clamp<std::uint32_t>(samples, 1, 16) * std::clamp<std::uint32_t>((bits + 7) / 8, 1, 8));
    return hd;
  }
  return std::nullopt;
}

void CheckImageDimensions(const fs::path& file, long long w, long long h, int bytes_per_pixel) {
  if (w <= 0 || h <= 0) throw InputError(file, "has an empty image size " + std::to_string(w) + "x" + std::to_string(h));
  const std::string size = std::to_string(w) + "x" + std::to_string(h);
  if (w > kMaxImageSide || h > kMaxImageSide || std::uint64_t(w) * std::uint64_t(h) > kMaxImagePixels)
    throw InputError(file, "claims " + size + " pixels, more than this program reads (" +
                               std::to_string(kMaxImagePixels >> 20) + " Mpx, sides up to " +
                               std::to_string(kMaxImageSide) + ")");
  // Decoding needs the image and about one converted copy.
  const std::uint64_t need = 2 * std::uint64_t(w) * std::uint64_t(h) * std::uint64_t(std::max(1, bytes_per_pixel));
  if (const auto free = AvailableHostBytes(); free && need > *free)
    throw InputError(file, "is a " + size + " image: decoding it needs about " + Mib(need) + ", and the machine has " +
                               Mib(*free) + " free");
}

}  // namespace hdrf
