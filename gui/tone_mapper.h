// Tone mapping for the studio's HDR views and the mesh colours: exposure (stops, relative to
// the image's own log-average so that views stay readable under auto exposure), an operator
// (linear clip or global Reinhard), display gamma, then the OpenColorIO display/view
// transform of the shipped config (resources/ocio/config.ocio: sRGB display).
#pragma once

#include <QImage>
#include <QString>
#include <memory>
#include <vector>

#include "common/image.h"

namespace hdrf::gui {

struct ToneSettings {
  enum class Operator { kLinear, kReinhard };
  Operator op = Operator::kReinhard;
  float exposure_stops = 0;  // added to the automatic key
  float gamma = 1.0f;        // extra display gamma on top of the sRGB curve (1 = none)
  bool auto_key = true;      // normalise by the log-average luminance first
};

class ToneMapper {
 public:
  // Loads the OCIO config from the Qt resource ":/ocio/config.ocio" (or `config_file`);
  // throws hdrf::Error naming the file when it cannot be read or parsed.
  explicit ToneMapper(const QString& config_file = QStringLiteral(":/ocio/config.ocio"));
  ~ToneMapper();
  ToneMapper(const ToneMapper&) = delete;
  ToneMapper& operator=(const ToneMapper&) = delete;

  // Display and view names of the config ("sRGB", "Standard").
  QString display() const;
  QString view() const;

  // Linear radiance to an 8-bit display image; pixels with no data (all zero) stay black.
  QImage Map(const RadianceImage& radiance, const ToneSettings& s) const;
  // The same mapping for a list of colours (mesh vertices), with the key of that list.
  std::vector<Rgb8> MapColours(const std::vector<Float3>& radiance, const ToneSettings& s) const;
  // The display transform alone on linear values in [0, 1] (for tests): in place.
  void DisplayTransform(float* rgb, long pixels) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hdrf::gui
