#include "gui/tone_mapper.h"

#include <OpenColorIO/OpenColorIO.h>

#include <QFile>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "tonemap/display.h"

namespace OCIO = OCIO_NAMESPACE;

namespace hdrf::gui {

struct ToneMapper::Impl {
  OCIO::ConstConfigRcPtr config;
  OCIO::ConstCPUProcessorRcPtr cpu;
  std::string display, view;
};

ToneMapper::ToneMapper(const QString& file) : impl_(std::make_unique<Impl>()) {
  QFile f(file);
  if (!f.open(QIODevice::ReadOnly))
    throw Error(file.toStdString() + ": cannot read the OpenColorIO config: " + f.errorString().toStdString());
  std::istringstream in(f.readAll().toStdString());
  try {
    impl_->config = OCIO::Config::CreateFromStream(in);
    impl_->config->validate();
    impl_->display = impl_->config->getDefaultDisplay();
    impl_->view = impl_->config->getDefaultView(impl_->display.c_str());
    auto t = OCIO::DisplayViewTransform::Create();
    t->setSrc(OCIO::ROLE_SCENE_LINEAR);
    t->setDisplay(impl_->display.c_str());
    t->setView(impl_->view.c_str());
    impl_->cpu = impl_->config->getProcessor(t)->getDefaultCPUProcessor();
  } catch (const OCIO::Exception& e) {
    throw Error(file.toStdString() + ": OpenColorIO config: " + e.what());
  }
}

ToneMapper::~ToneMapper() = default;

QString ToneMapper::display() const { return QString::fromStdString(impl_->display); }
QString ToneMapper::view() const { return QString::fromStdString(impl_->view); }

void ToneMapper::DisplayTransform(float* rgb, long pixels) const {
  OCIO::PackedImageDesc desc(rgb, pixels, 1, 3);
  impl_->cpu->apply(desc);
}

namespace {
// Exposure and operator in linear light; result in [0, 1] per channel.
void ToLinearDisplay(const Float3* in, std::size_t n, const ToneSettings& s, std::vector<float>& out) {
  const float key = s.auto_key ? 0.18f / tonemap::LogAverageLuminance(in, n) : 1.f;
  const float scale = key * std::exp2(s.exposure_stops);
  out.resize(n * 3);
  for (std::size_t i = 0; i < n; ++i) {
    Float3 c = in[i] * scale;
    if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z))) c = {0, 0, 0};
    if (s.op == ToneSettings::Operator::kReinhard) c = tonemap::ReinhardPixel(c);
    const float v[3] = {c.x, c.y, c.z};
    for (int k = 0; k < 3; ++k) {
      float x = std::clamp(v[k], 0.f, 1.f);
      if (s.gamma != 1.f) x = std::pow(x, 1.f / s.gamma);
      out[i * 3 + std::size_t(k)] = x;
    }
  }
}
std::uint8_t To8(float x) { return std::uint8_t(std::lround(std::clamp(x, 0.f, 1.f) * 255.f)); }
}  // namespace

QImage ToneMapper::Map(const RadianceImage& r, const ToneSettings& s) const {
  std::vector<float> lin;
  ToLinearDisplay(r.data(), r.size(), s, lin);
  DisplayTransform(lin.data(), long(r.size()));
  QImage img(r.width(), r.height(), QImage::Format_RGB888);
  for (int y = 0; y < r.height(); ++y) {
    std::uint8_t* row = img.scanLine(y);
    for (int x = 0; x < r.width(); ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(r.width()) + std::size_t(x);
      for (int k = 0; k < 3; ++k) row[3 * x + k] = To8(lin[3 * i + std::size_t(k)]);
    }
  }
  return img;
}

std::vector<Rgb8> ToneMapper::MapColours(const std::vector<Float3>& r, const ToneSettings& s) const {
  std::vector<float> lin;
  ToLinearDisplay(r.data(), r.size(), s, lin);
  if (!r.empty()) DisplayTransform(lin.data(), long(r.size()));
  std::vector<Rgb8> out(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) out[i] = {To8(lin[3 * i]), To8(lin[3 * i + 1]), To8(lin[3 * i + 2])};
  return out;
}

}  // namespace hdrf::gui
