// The OpenColorIO display/view transform: the last step of every tone-mapping operator
// (display-linear RGB to display code values). The shipped config (resources/ocio/
// config.ocio: an sRGB display) is compiled in; another config can be read from a file.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/image.h"

namespace hdrf::io {

const char* BuiltinOcioConfig();

class OcioDisplay {
 public:
  // The built-in config with a display and view (empty: its defaults; throws Error naming
  // the display or view it lacks).
  explicit OcioDisplay(const std::string& display = "", const std::string& view = "");
  // A config file; empty display/view take the config's defaults. Throws InputError naming
  // the file (unreadable, invalid, or without the display or view asked for).
  explicit OcioDisplay(const std::filesystem::path& config, const std::string& display = "",
                       const std::string& view = "");
  ~OcioDisplay();
  OcioDisplay(const OcioDisplay&) = delete;
  OcioDisplay& operator=(const OcioDisplay&) = delete;

  const std::string& display() const;
  const std::string& view() const;

  // In place on packed RGB floats (display-linear in, display code values out).
  void Apply(float* rgb, long pixels) const;
  void Apply(Image<Float3>& img) const { Apply(&img.data()->x, long(img.size())); }
  // Display-linear colours (mesh vertices) to 8-bit display colours.
  std::vector<Rgb8> Encode(std::vector<Float3> display_linear) const;
  // Display code values as 8-bit colour (clamped, rounded; not finite is 0).
  static ColorImage Quantise(const Image<Float3>& encoded);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hdrf::io
