// Tone mapping for the studio's HDR views and the mesh colours: any declared operator
// (core/tonemap), one instance per view so each keeps its own temporal filter, then the
// OpenColorIO display/view transform (io::OcioDisplay; the built-in config is an sRGB
// display). The mesh colours follow the model view's operator (its curve from the model
// render), so the 3-D view and the model view agree.
#pragma once

#include <QImage>
#include <QString>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/image.h"
#include "io/ocio_display.h"
#include "tonemap/operator.h"

namespace hdrf::gui {

// Which view a mapping is for (each has its own operator state).
enum class ToneView { kLive, kModel, kOther };

// The operator and its parameters as the user set them (values not set take the defaults).
struct ToneChoice {
  std::string op = "mantiuk08";
  tonemap::Params values;
};

class ToneMapper {
 public:
  // The built-in OCIO config, or a config file (throws hdrf::Error naming the file).
  ToneMapper();
  explicit ToneMapper(const QString& config_file);
  ~ToneMapper();
  ToneMapper(const ToneMapper&) = delete;
  ToneMapper& operator=(const ToneMapper&) = delete;

  QString display() const;
  QString view() const;

  // Switches operator or parameters (checked: throws SettingError); the views' filters
  // start over.
  void Set(const ToneChoice& c);
  const ToneChoice& choice() const { return choice_; }
  // Where the Mantiuk operators run (CUDA falls back to the CPU where it cannot be used).
  void SetDevice(Device d);

  // Linear radiance to an 8-bit display image; `seconds` is the frame's time for the
  // temporal filters (negative: a still). Pixels with no data stay black.
  QImage Map(const RadianceImage& radiance, ToneView v = ToneView::kOther, double seconds = -1);
  // Mesh vertex colours, with the model view's curve where it has mapped a render.
  std::vector<Rgb8> MapColours(const std::vector<Float3>& radiance);
  // The tone curve the view's operator used last (empty for local operators).
  tonemap::Operator::Curve LastCurve(ToneView v) { return For(v).LastCurve(); }
  // The display transform alone on display-linear values in [0, 1] (for tests): in place.
  void DisplayTransform(float* rgb, long pixels) const;

 private:
  tonemap::Operator& For(ToneView v);
  std::unique_ptr<io::OcioDisplay> ocio_;
  ToneChoice choice_;
  tonemap::Params params_;
  std::map<ToneView, std::unique_ptr<tonemap::Operator>> ops_;
  Device device_ = Device::kCpu;
};

}  // namespace hdrf::gui
