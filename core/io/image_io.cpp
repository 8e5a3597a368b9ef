#include "io/image_io.h"

#include <cmath>
#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/input_file.h"
#include "io/output_file.h"
#include "common/error.h"

namespace hdrf::io {

namespace {

const char* DepthName(int cv_depth) {
  switch (cv_depth) {
    case CV_8U: return "8-bit";
    case CV_8S: return "8-bit signed";
    case CV_16U: return "16-bit";
    case CV_16S: return "16-bit signed";
    case CV_32F: return "32-bit float";
    default: return "unusual";
  }
}

// The file read once, its header's size checked (against this program's limits, the free
// memory, and `check_header` where given) before anything is decoded.
cv::Mat Load(const std::filesystem::path& file, const HeaderCheck& check_header) {
  const std::string bytes = ReadInputFile(file, kMaxImageBytes, "an image");
  // (OpenCV answers an empty buffer with an assertion, which was shown as the message)
  if (bytes.empty()) throw InputError(file, "is empty (0 bytes), not an image");
  // Only what can be sized from its header is decoded: a few kilobytes of another format can
  // describe gigabytes of pixels.
  const std::optional<ImageHeader> h = PeekImageHeader(file, bytes);
  if (!h) throw InputError(file, "is not a PNG, JPEG or TIFF image (the formats read)");
  CheckImageDimensions(file, h->width, h->height, h->bytes_per_pixel);
  if (check_header) check_header(h->width, h->height);
  cv::Mat m;
  try {
    m = cv::imdecode(cv::Mat(1, int(bytes.size()), CV_8U, const_cast<char*>(bytes.data())), cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw InputError(file, std::string("cannot be decoded as an image: ") + e.what());
  }
  if (m.empty()) throw InputError(file, "cannot be decoded as an image (corrupt or truncated?)");
  if (check_header) check_header(m.cols, m.rows);
  return m;
}

void Save(const std::filesystem::path& file, const cv::Mat& m) {
  std::vector<std::uint8_t> png;
  bool ok = false;
  try {
    ok = cv::imencode(".png", m, png);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw InputError(file, "cannot be written as PNG");
  WriteFileAtomically(file, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace

HeaderCheck ExpectSize(const std::filesystem::path& file, int width, int height) {
  return [file, width, height](int w, int h) {
    if (w != width || h != height)
      throw InputError(file, "image is " + std::to_string(w) + "x" + std::to_string(h) + " but sensor.json says " +
                                 std::to_string(width) + "x" + std::to_string(height));
  };
}

ColorImage ReadColorImage(const std::filesystem::path& file, const HeaderCheck& check_header) {
  cv::Mat m = Load(file, check_header);
  if (m.depth() != CV_8U)
    throw InputError(file, std::string("colour image must be 8-bit, found ") +
                               DepthName(m.depth()));
  if (m.channels() != 3 && m.channels() != 4)
    throw InputError(file, "colour image must have 3 channels (RGB), found " +
                               std::to_string(m.channels()));
  cv::Mat rgb;
  cv::cvtColor(m, rgb, m.channels() == 4 ? cv::COLOR_BGRA2RGB : cv::COLOR_BGR2RGB);
  ColorImage out(rgb.cols, rgb.rows);
  for (int y = 0; y < rgb.rows; ++y)
    std::memcpy(&out(0, y), rgb.ptr<std::uint8_t>(y), std::size_t(rgb.cols) * 3);
  return out;
}

DepthRawImage ReadDepthImage(const std::filesystem::path& file, const HeaderCheck& check_header) {
  cv::Mat m = Load(file, check_header);
  if (m.depth() != CV_16U)
    throw InputError(file, std::string("depth image must be 16-bit unsigned, found ") +
                               DepthName(m.depth()));
  if (m.channels() != 1)
    throw InputError(file, "depth image must have 1 channel, found " +
                               std::to_string(m.channels()));
  DepthRawImage out(m.cols, m.rows);
  for (int y = 0; y < m.rows; ++y)
    std::memcpy(&out(0, y), m.ptr<std::uint16_t>(y), std::size_t(m.cols) * 2);
  return out;
}

void WriteColorPng(const std::filesystem::path& file, const ColorImage& image) {
  cv::Mat rgb(image.height(), image.width(), CV_8UC3, const_cast<Rgb8*>(image.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  Save(file, bgr);
}

std::vector<std::uint8_t> EncodeColorPng(const ColorImage& image) {
  cv::Mat rgb(image.height(), image.width(), CV_8UC3, const_cast<Rgb8*>(image.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<std::uint8_t> out;
  if (!cv::imencode(".png", bgr, out)) throw Error("PNG encoding failed");
  return out;
}

ColorImage DecodeColorPng(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes,
                          const std::string& what) {
  const std::string head(reinterpret_cast<const char*>(bytes.data()), std::min<std::size_t>(bytes.size(), 64));
  const std::optional<ImageHeader> h = PeekImageHeader(file, head);
  if (!h) throw InputError(file, what + " is not a PNG image");
  CheckImageDimensions(file, h->width, h->height, h->bytes_per_pixel);
  const cv::Mat m = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  if (m.empty() || m.depth() != CV_8U || m.channels() != 3)
    throw InputError(file, what + " is not an 8-bit RGB PNG image");
  cv::Mat rgb;
  cv::cvtColor(m, rgb, cv::COLOR_BGR2RGB);
  ColorImage out(rgb.cols, rgb.rows);
  for (int y = 0; y < rgb.rows; ++y) std::memcpy(&out(0, y), rgb.ptr<std::uint8_t>(y), std::size_t(rgb.cols) * 3);
  return out;
}

void WriteDepthPng(const std::filesystem::path& file, const DepthRawImage& image) {
  cv::Mat m(image.height(), image.width(), CV_16UC1, const_cast<std::uint16_t*>(image.data()));
  Save(file, m);
}

DepthImage DepthToMetres(const DepthRawImage& raw, double scale) {
  DepthImage out(raw.width(), raw.height());
  const float inv = float(1.0 / scale);
  // 65535, the largest code, is no measurement: sensors and datasets (7-Scenes among them)
  // mark invalid pixels with it as well as with 0, and read as depth it is a point tens of
  // metres away that tracking and fusion would take for a surface.
  for (std::size_t i = 0; i < raw.size(); ++i) out[i] = raw[i] == kDepthInvalidMax ? 0.f : float(raw[i]) * inv;
  return out;
}

DepthRawImage DepthFromMetres(const DepthImage& depth_m, double scale) {
  DepthRawImage out(depth_m.width(), depth_m.height());
  for (std::size_t i = 0; i < depth_m.size(); ++i) {
    const double v = std::round(double(depth_m[i]) * scale);
    out[i] = (std::isfinite(v) && v > 0) ? std::uint16_t(std::min(v, double(kDepthInvalidMax - 1))) : 0;
  }
  return out;
}

}  // namespace hdrf::io
