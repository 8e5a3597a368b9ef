#include "io/exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <half.h>

#include <cmath>
#include <vector>

#include "common/error.h"
#include "io/text_table.h"

namespace hdrf::io {

RadianceImage ReadExr(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw InputError(file, "OpenEXR file is missing");
  try {
    Imf::InputFile in(file.string().c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1;
    const int h = dw.max.y - dw.min.y + 1;
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
  const auto tmp = TemporarySibling(file);
  try {
    Imf::Header header(image.width(), image.height());
    header.compression() = Imf::ZIP_COMPRESSION;
    const Imf::PixelType type = precision == ExrPrecision::kHalf ? Imf::HALF : Imf::FLOAT;
    const char* names[3] = {"R", "G", "B"};
    for (const char* n : names) header.channels().insert(n, Imf::Channel(type));
    Imf::OutputFile out(tmp.string().c_str(), header);
    // The output file does not convert between pixel types: give it what the file holds.
    Imf::FrameBuffer fb;
    std::vector<half> halves;
    if (type == Imf::HALF) {
      halves.resize(image.size() * 3);
      for (std::size_t i = 0; i < image.size(); ++i) {
        halves[3 * i] = half(image[i].x);
        halves[3 * i + 1] = half(image[i].y);
        halves[3 * i + 2] = half(image[i].z);
      }
      char* base = reinterpret_cast<char*>(halves.data());
      const std::size_t xs = 3 * sizeof(half), ys = xs * std::size_t(image.width());
      for (int c = 0; c < 3; ++c)
        fb.insert(names[c], Imf::Slice(Imf::HALF, base + c * sizeof(half), xs, ys));
    } else {
      char* base = reinterpret_cast<char*>(const_cast<Float3*>(image.data()));
      const std::size_t xs = sizeof(Float3), ys = sizeof(Float3) * std::size_t(image.width());
      for (int c = 0; c < 3; ++c)
        fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
    }
    out.setFrameBuffer(fb);
    out.writePixels(image.height());
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw InputError(file, std::string("cannot be written as OpenEXR: ") + e.what());
  }
  CommitTemporary(tmp, file);
}

}  // namespace hdrf::io
