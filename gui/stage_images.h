// The engine's images as the studio's views draw them: 32-bit RGB pictures (the format Qt
// paints without converting it first) and the words a view shows for the pixel under the
// pointer.
#pragma once

#include <QImage>
#include <QString>
#include <QVector>

#include "common/image.h"
#include "common/vec.h"

namespace hdrf::gui {

QImage FromColor(const ColorImage& c);
// A scalar image to grey over [lo, hi]; pixels that `valid` refuses are drawn dark blue (no
// data).
QImage Grey(const Image<float>& im, float lo, float hi, bool (*valid)(float));
// Unit normals as colours (each axis from -1..1 to 0..255); no surface dark blue.
QImage NormalsImage(const Image<Float3>& n);
// Scale bars (64 colours, lowest first): grey, and the depth colours over [0, hi] m.
QVector<QRgb> GreyBar();
QVector<QRgb> DepthBar(float hi);
// The largest value of an image, at least `floor` (a scale bar's top).
float LargestValue(const Image<float>& im, float floor);
// "radiance R G B" for a pixel's readout.
QString RadianceText(Float3 r);

}  // namespace hdrf::gui
