#include "io/exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <set>
#include <vector>

#include "common/input_file.h"
#include "io/output_file.h"
#include "common/error.h"

namespace hdrf::io {

namespace {
// The data window's size, checked before any pixel is allocated.
std::pair<int, int> CheckedSize(const std::filesystem::path& file, const Imath::Box2i& dw, int bytes_per_pixel) {
  const long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
  CheckImageDimensions(file, w, h, bytes_per_pixel);
  return {int(w), int(h)};
}

// Walks the file's headers (every part's, for a multi-part file) without OpenEXR: no
// attribute may claim more bytes than the file holds, the first part's data window must be a
// sane size, and a single-part file must be large enough for the chunk offset table that
// size implies. OpenEXR allocates attribute values and that table from the header alone, so
// a small file claiming huge ones is refused here before it costs any memory.
void CheckExrHeader(const std::filesystem::path& file, std::uintmax_t file_bytes, std::size_t read_bytes);

// Headers are small: the first 64 KiB are read, and up to 16 MiB only for a header longer
// than that (a large preview or profile attribute), so a large image is not read twice.
void CheckExrHeader(const std::filesystem::path& file, std::uintmax_t file_bytes) {
  constexpr std::size_t kFirst = 64 << 10;
  if (file_bytes <= kFirst) return CheckExrHeader(file, file_bytes, kFirst);
  try {
    CheckExrHeader(file, file_bytes, kFirst);
  } catch (const InputError&) {
    CheckExrHeader(file, file_bytes, 16 << 20);  // the same verdict where the header fits
  }
}

void CheckExrHeader(const std::filesystem::path& file, std::uintmax_t file_bytes, std::size_t read_bytes) {
  std::ifstream in(file, std::ios::binary);
  std::string b(std::size_t(std::min<std::uintmax_t>(file_bytes, read_bytes)), '\0');
  in.read(b.data(), std::streamsize(b.size()));
  b.resize(std::size_t(in.gcount()));
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = (v << 8) | std::uint8_t(b[at + std::size_t(k)]);
    return v;
  };
  if (b.size() < 8 || u32(0) != 20000630u) throw InputError(file, "is not an OpenEXR file (no OpenEXR magic number)");
  const std::uint32_t flags = u32(4);
  const bool tiled = flags & 0x200u, multi_part = flags & 0x1000u, deep = flags & 0x800u;
  std::size_t at = 8;
  // Names and type names: at most 31 bytes, 255 in files flagged for long names (OpenEXR
  // reads no further, so a longer one would be read by it differently than here).
  const std::size_t max_name = (flags & 0x400u) ? 255 : 31;
  const auto cstring = [&](std::string& out) {
    const std::size_t end = b.find('\0', at);
    if (end == std::string::npos || end - at > max_name) return false;
    out = b.substr(at, end - at);
    at = end + 1;
    return true;
  };
  const auto damaged = [&] {
    return InputError(file, "OpenEXR header is damaged (a name too long, or an attribute running past the end of the "
                            "file or a header longer than 16 MiB)");
  };
  std::optional<Imath::Box2i> window;
  int compression = -1;
  // Scan lines per chunk by compression: none, RLE, ZIPS 1; ZIP, PXR24 16; PIZ, B44(A),
  // DWAA 32; DWAB 256.
  static constexpr int kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  const auto lines = [&] { return compression >= 0 && compression < 10 ? kLines[compression] : 1; };
  std::uint32_t tile_x = 0, tile_y = 0;
  std::uint64_t pixel_bytes = 0;  // all channels of one pixel
  for (int part = 0;; ++part) {
    bool empty = true;
    std::set<std::string> names;
    for (;;) {
      std::string name, type;
      if (!cstring(name)) throw damaged();
      if (name.empty()) break;  // the end of this header
      empty = false;
      // Named twice: which value OpenEXR keeps is not this check's to guess.
      if (!names.insert(name).second)
        throw InputError(file, "OpenEXR header names the attribute '" + name + "' twice (damaged)");
      if (!cstring(type) || at + 4 > b.size()) throw damaged();
      const std::uint32_t size = u32(at);
      at += 4;
      if (size > b.size() - at) throw damaged();
      if (part == 0) {
        if (name == "dataWindow" && type == "box2i" && size == 16)
          window = Imath::Box2i({int(u32(at)), int(u32(at + 4))}, {int(u32(at + 8)), int(u32(at + 12))});
        if (name == "compression" && type == "compression" && size == 1) compression = std::uint8_t(b[at]);
        if (name == "tiles" && type == "tiledesc" && size >= 8) tile_x = u32(at), tile_y = u32(at + 4);
        if (name == "channels" && type == "chlist") {
          // Each channel: name, pixel type (0 uint, 1 half, 2 float), 4 bytes, x and y sampling.
          std::size_t c = at;
          const std::size_t end = at + size;
          while (c < end && b[c] != '\0') {
            const std::size_t name_end = b.find('\0', c);
            if (name_end == std::string::npos || name_end + 17 > end) throw damaged();
            const std::uint32_t pixel_type = u32(name_end + 1);
            pixel_bytes += pixel_type == 1 ? 2 : 4;
            c = name_end + 17;
          }
        }
      }
      at += size;
    }
    // A single-part file has one header; a multi-part file's list ends with an empty one.
    if (!multi_part || empty) break;
  }
  if (!window) throw InputError(file, "OpenEXR header has no data window");
  // The window's origin within 2^24 pixels of the image origin: the offset of its first
  // pixel stays far inside the address space.
  constexpr int kFar = 1 << 24;
  if (std::abs((long long)window->min.x) > kFar || std::abs((long long)window->min.y) > kFar)
    throw InputError(file, "OpenEXR data window starts at (" + std::to_string(window->min.x) + ", " +
                               std::to_string(window->min.y) + "), more than " + std::to_string(kFar) +
                               " pixels from the origin");
  const long long w = (long long)window->max.x - window->min.x + 1, h = (long long)window->max.y - window->min.y + 1;
  CheckImageDimensions(file, w, h, 1);
  // OpenEXR decodes a whole chunk (every channel) at once: a header with many channels and a
  // wide window would make it allocate gigabytes for one chunk (the fuzzer's 1.3 KB file asked
  // for 1.9 GB). 256 MiB holds a 65536-pixel-wide, 32-line chunk of 32 float channels.
  {
    constexpr std::uint64_t kMaxChunkBytes = std::uint64_t(256) << 20;
    const std::uint64_t chunk_pixels = tiled ? std::uint64_t(tile_x) * tile_y : std::uint64_t(w) * std::uint64_t(lines());
    if (pixel_bytes > 0 && chunk_pixels > kMaxChunkBytes / pixel_bytes)
      throw InputError(file, "OpenEXR header describes chunks of " + std::to_string((chunk_pixels * pixel_bytes) >> 20) +
                                 " MiB (" + std::to_string(pixel_bytes) + " bytes per pixel), more than the " +
                                 std::to_string(kMaxChunkBytes >> 20) + " MiB a chunk may decode to");
  }
  if (multi_part || deep) return;  // their offset tables are sized per part: OpenEXR's checks
  // Level 0's chunks alone need one 8-byte offset each.
  long long chunks = 0;
  if (tiled) {
    if (tile_x == 0 || tile_y == 0) throw InputError(file, "OpenEXR tiled image has no tile size");
    chunks = ((w + tile_x - 1) / tile_x) * ((h + tile_y - 1) / tile_y);
  } else {
    chunks = (h + lines() - 1) / lines();
  }
  if (std::uintmax_t(at) + std::uintmax_t(chunks) * 8 > file_bytes)
    throw InputError(file, "OpenEXR file is too short for the " + std::to_string(w) + "x" + std::to_string(h) +
                               " image its header describes (truncated or damaged)");
}

void CheckExrFile(const std::filesystem::path& file) {
  CheckExrHeader(file, CheckInputFile(file, 4 * kMaxImageBytes, "an OpenEXR image"));
}
}  // namespace

RadianceImage ReadExr(const std::filesystem::path& file) {
  CheckExrFile(file);
  try {
    Imf::InputFile in(file.string().c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const auto [w, h] = CheckedSize(file, dw, sizeof(Float3));
    const Imf::ChannelList& ch = in.header().channels();
    const bool rgb = ch.findChannel("R") && ch.findChannel("G") && ch.findChannel("B");
    const bool y_only = !rgb && ch.findChannel("Y");
    if (!rgb && !y_only) throw InputError(file, "OpenEXR file has no R, G, B (or Y) channels");
    RadianceImage out(w, h);
    // Slices addressed from the data window (OpenEXR computes the origin's offset, with no
    // pointer arithmetic outside the image here).
    const std::size_t xs = sizeof(Float3), ys = sizeof(Float3) * std::size_t(w);
    Imf::FrameBuffer fb;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
      fb.insert(rgb ? names[c] : "Y",
                Imf::Slice::Make(Imf::FLOAT, reinterpret_cast<char*>(out.data()) + c * sizeof(float), dw, xs, ys));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < out.size(); ++i)
      if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z)) ++bad;
    if (bad)
      throw InputError(file, std::to_string(bad) + " pixel(s) are NaN or infinite");
    return out;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(file, std::string("cannot be read as OpenEXR: ") + e.what());
  }
}

void WriteExr(const std::filesystem::path& file, const RadianceImage& image,
              ExrPrecision precision) {
  ExrWriteOptions o;
  o.precision = precision;
  WriteExr(file, image, o);
}

namespace {
// OpenEXR writes through this into an OutputFile's stream (it seeks back for the line offsets).
class OutputStream : public Imf::OStream {
 public:
  OutputStream(std::ostream& os, const std::filesystem::path& file) : Imf::OStream(file.c_str()), os_(os) {}
  void write(const char c[], int n) override {
    os_.write(c, n);
    if (!os_) throw std::runtime_error("write failed (disk full?)");
  }
  uint64_t tellp() override { return uint64_t(os_.tellp()); }
  void seekp(uint64_t pos) override {
    os_.seekp(std::streamoff(pos));
    if (!os_) throw std::runtime_error("seek failed");
  }

 private:
  std::ostream& os_;
};
}  // namespace

void WriteExr(const std::filesystem::path& file, const RadianceImage& image, const ExrWriteOptions& o) {
  for (const ExrChannel& c : o.extra)
    if (!c.image || c.image->width() != image.width() || c.image->height() != image.height())
      throw Error("OpenEXR channel '" + c.name + "' differs in size from the image (" + file.string() + ")");
  OutputFile staged(file);
  try {
    Imf::Header header(image.width(), image.height());
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [key, value] : o.attributes) header.insert(key, Imf::StringAttribute(value));
    // Planes as the file holds them (the output file does not convert between pixel types).
    struct Plane {
      std::string name;
      Imf::PixelType type;
      std::vector<half> h;
      std::vector<float> f;
    };
    std::vector<Plane> planes;
    const std::size_t n = image.size();
    const auto add = [&](const std::string& name, ExrPrecision p, auto get) {
      Plane pl{name, p == ExrPrecision::kHalf ? Imf::HALF : Imf::FLOAT, {}, {}};
      if (pl.type == Imf::HALF) {
        pl.h.resize(n);
        for (std::size_t i = 0; i < n; ++i) pl.h[i] = half(get(i));
      } else {
        pl.f.resize(n);
        for (std::size_t i = 0; i < n; ++i) pl.f[i] = get(i);
      }
      planes.push_back(std::move(pl));
    };
    add("R", o.precision, [&](std::size_t i) { return image[i].x; });
    add("G", o.precision, [&](std::size_t i) { return image[i].y; });
    add("B", o.precision, [&](std::size_t i) { return image[i].z; });
    for (const ExrChannel& c : o.extra) add(c.name, c.precision, [&](std::size_t i) { return (*c.image)[i]; });
    Imf::FrameBuffer fb;
    for (Plane& pl : planes) {
      header.channels().insert(pl.name, Imf::Channel(pl.type));
      const std::size_t size = pl.type == Imf::HALF ? sizeof(half) : sizeof(float);
      char* base = pl.type == Imf::HALF ? reinterpret_cast<char*>(pl.h.data()) : reinterpret_cast<char*>(pl.f.data());
      fb.insert(pl.name, Imf::Slice(pl.type, base, size, size * std::size_t(image.width())));
    }
    OutputStream os(staged.stream(), file);
    Imf::OutputFile out(os, header);
    out.setFrameBuffer(fb);
    out.writePixels(image.height());
  } catch (const std::exception& e) {
    throw InputError(file, std::string("cannot be written as OpenEXR: ") + e.what());
  }
  staged.Commit();
}

Image<float> ReadExrChannel(const std::filesystem::path& file, const std::string& name) {
  CheckExrFile(file);
  try {
    Imf::InputFile in(file.string().c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const auto [w, h] = CheckedSize(file, dw, sizeof(float));
    if (!in.header().channels().findChannel(name)) throw InputError(file, "OpenEXR file has no channel '" + name + "'");
    Image<float> out(w, h);
    Imf::FrameBuffer fb;
    fb.insert(name, Imf::Slice::Make(Imf::FLOAT, out.data(), dw, sizeof(float), sizeof(float) * std::size_t(w)));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return out;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(file, std::string("cannot be read as OpenEXR: ") + e.what());
  }
}

std::optional<std::string> ReadExrAttribute(const std::filesystem::path& file, const std::string& name) {
  CheckExrFile(file);
  try {
    Imf::InputFile in(file.string().c_str());
    const auto* a = in.header().findTypedAttribute<Imf::StringAttribute>(name);
    if (!a) return std::nullopt;
    return a->value();
  } catch (const std::exception& e) {
    throw InputError(file, std::string("cannot be read as OpenEXR: ") + e.what());
  }
}

}  // namespace hdrf::io
