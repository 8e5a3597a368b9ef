#include "gui/tone_mapper.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace hdrf::gui {

ToneMapper::ToneMapper() : ocio_(std::make_unique<io::OcioDisplay>()) { Set({}); }

ToneMapper::ToneMapper(const QString& file) : ocio_(std::make_unique<io::OcioDisplay>(file.toStdString())) { Set({}); }

ToneMapper::~ToneMapper() = default;

QString ToneMapper::display() const { return QString::fromStdString(ocio_->display()); }
QString ToneMapper::view() const { return QString::fromStdString(ocio_->view()); }

void ToneMapper::Set(const ToneChoice& c) {
  const tonemap::OperatorDecl& d = tonemap::FindOperator(c.op);
  params_ = tonemap::ResolveParams(d, c.values);
  choice_ = c;
  ops_.clear();
}

tonemap::Operator& ToneMapper::For(ToneView v) {
  auto& op = ops_[v];
  if (!op) {
    const auto& d = tonemap::FindOperator(choice_.op);
    try {
      op = d.make(params_, device_);
    } catch (const Error&) {
      op = d.make(params_, Device::kCpu);  // no usable GPU: the CPU gives the same result
    }
  }
  return *op;
}

void ToneMapper::SetDevice(Device d) {
  if (d == device_) return;
  device_ = d;
  ops_.clear();
}

void ToneMapper::DisplayTransform(float* rgb, long pixels) const { ocio_->Apply(rgb, pixels); }

namespace {
std::uint8_t To8(float x) { return std::uint8_t(std::lround(std::clamp(std::isfinite(x) ? x : 0.f, 0.f, 1.f) * 255.f)); }
}  // namespace

QImage ToneMapper::Map(const RadianceImage& r, ToneView v, double seconds) {
  Image<Float3> lin;
  For(v).Map(r, lin, tonemap::FrameTime{seconds});
  ocio_->Apply(lin);
  QImage img(r.width(), r.height(), QImage::Format_RGB32);  // painted without a conversion
  for (int y = 0; y < r.height(); ++y) {
    auto* row = reinterpret_cast<QRgb*>(img.scanLine(y));
    for (int x = 0; x < r.width(); ++x) {
      const Float3 c = lin(x, y);
      row[x] = qRgb(To8(c.x), To8(c.y), To8(c.z));
    }
  }
  return img;
}

std::vector<Rgb8> ToneMapper::MapColours(const std::vector<Float3>& r) {
  return ocio_->Encode(For(ToneView::kModel).MapList(r));
}

}  // namespace hdrf::gui
