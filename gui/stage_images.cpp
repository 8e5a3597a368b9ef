#include "gui/stage_images.h"

#include <QObject>
#include <algorithm>
#include <cmath>

#include "tonemap/display.h"

namespace hdrf::gui {

namespace {
constexpr QRgb kNoData = 0xff000028;  // qRgb(0, 0, 40)
}

QImage FromColor(const ColorImage& c) {
  QImage img(c.width(), c.height(), QImage::Format_RGB32);
  for (int y = 0; y < c.height(); ++y) {
    auto* row = reinterpret_cast<QRgb*>(img.scanLine(y));
    for (int x = 0; x < c.width(); ++x) row[x] = qRgb(c(x, y).r, c(x, y).g, c(x, y).b);
  }
  return img;
}

QImage Grey(const Image<float>& im, float lo, float hi, bool (*valid)(float)) {
  QImage img(im.width(), im.height(), QImage::Format_RGB32);
  for (int y = 0; y < im.height(); ++y) {
    auto* row = reinterpret_cast<QRgb*>(img.scanLine(y));
    for (int x = 0; x < im.width(); ++x) {
      const float v = im(x, y);
      if (!valid(v)) {
        row[x] = kNoData;
        continue;
      }
      const int g = int(std::lround(255.f * std::clamp((v - lo) / (hi - lo), 0.f, 1.f)));
      row[x] = qRgb(g, g, g);
    }
  }
  return img;
}

QImage NormalsImage(const Image<Float3>& n) {
  QImage img(n.width(), n.height(), QImage::Format_RGB32);
  for (int y = 0; y < n.height(); ++y) {
    auto* row = reinterpret_cast<QRgb*>(img.scanLine(y));
    for (int x = 0; x < n.width(); ++x) {
      const Float3 v = n(x, y);
      row[x] = Length(v) > 0 ? qRgb(int(127.5f * (v.x + 1)), int(127.5f * (v.y + 1)), int(127.5f * (v.z + 1))) : kNoData;
    }
  }
  return img;
}

QVector<QRgb> GreyBar() {
  QVector<QRgb> bar;
  for (int i = 0; i < 64; ++i) bar.push_back(qRgb(i * 4 + 3, i * 4 + 3, i * 4 + 3));
  return bar;
}

QVector<QRgb> DepthBar(float hi) {
  DepthImage ramp(1, 64);
  for (int i = 0; i < 64; ++i) ramp(0, i) = std::max(1e-3f, hi * float(i) / 63.f);
  const ColorImage rc = tonemap::ColorizeDepth(ramp, 0.f, hi);
  QVector<QRgb> bar;
  for (int i = 0; i < 64; ++i) bar.push_back(qRgb(rc(0, i).r, rc(0, i).g, rc(0, i).b));
  return bar;
}

float LargestValue(const Image<float>& im, float floor) {
  float mx = floor;
  for (std::size_t i = 0; i < im.size(); ++i) mx = std::max(mx, im[i]);
  return mx;
}

QString RadianceText(Float3 r) {
  return QObject::tr("radiance %1 %2 %3").arg(r.x, 0, 'g', 4).arg(r.y, 0, 'g', 4).arg(r.z, 0, 'g', 4);
}

}  // namespace hdrf::gui
