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

#include <cmath>
#include <vector>

#include "io/input_file.h"
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

void CheckExrFile(const std::filesystem::path& file) { CheckInputFile(file, 4 * kMaxImageBytes, "an OpenEXR image"); }
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
    char* base = reinterpret_cast<char*>(out.data()) -
                 (std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * w) * sizeof(Float3);
    const std::size_t xs = sizeof(Float3), ys = sizeof(Float3) * std::size_t(w);
    Imf::FrameBuffer fb;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
      fb.insert(rgb ? names[c] : "Y", Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
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
    char* base = reinterpret_cast<char*>(out.data()) - (std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * w) * sizeof(float);
    Imf::FrameBuffer fb;
    fb.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * std::size_t(w)));
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
