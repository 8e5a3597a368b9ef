#include "eval/image_quality.h"

#include <array>
#include <cmath>

#include "common/error.h"

namespace hdrf::eval {

namespace {
constexpr int kRadius = 5;

// Separable Gaussian filter, "valid" region only: the output is (w - 10) x (h - 10).
Image<double> Filter(const Image<double>& in, const std::array<double, 2 * kRadius + 1>& g) {
  const int w = in.width(), h = in.height(), ow = w - 2 * kRadius, oh = h - 2 * kRadius;
  Image<double> tmp(ow, h), out(ow, oh);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int k = 0; k <= 2 * kRadius; ++k) s += g[std::size_t(k)] * in(x + k, y);
      tmp(x, y) = s;
    }
#pragma omp parallel for schedule(static)
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int k = 0; k <= 2 * kRadius; ++k) s += g[std::size_t(k)] * tmp(x, y + k);
      out(x, y) = s;
    }
  return out;
}
}  // namespace

double Ssim(const Image<float>& a, const Image<float>& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw Error("SSIM: the images differ in size (" + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                " against " + std::to_string(b.width()) + "x" + std::to_string(b.height()) + ")");
  if (a.width() <= 2 * kRadius || a.height() <= 2 * kRadius) throw Error("SSIM: the images are smaller than the 11x11 window");
  std::array<double, 2 * kRadius + 1> g{};
  double sum = 0;
  for (int k = -kRadius; k <= kRadius; ++k) sum += g[std::size_t(k + kRadius)] = std::exp(-k * k / (2 * 1.5 * 1.5));
  for (double& v : g) v /= sum;
  const int w = a.width(), h = a.height();
  Image<double> x(w, h), y(w, h), xx(w, h), yy(w, h), xy(w, h);
  for (std::size_t i = 0; i < a.size(); ++i) {
    x[i] = a[i], y[i] = b[i];
    xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
  }
  const Image<double> mx = Filter(x, g), my = Filter(y, g), sxx = Filter(xx, g), syy = Filter(yy, g), sxy = Filter(xy, g);
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  double total = 0;
  for (std::size_t i = 0; i < mx.size(); ++i) {
    const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cxy = sxy[i] - mx[i] * my[i];
    total += (2 * mx[i] * my[i] + c1) * (2 * cxy + c2) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
  }
  return total / double(mx.size());
}

Image<float> LuminanceOf(const Image<Float3>& rgb) {
  Image<float> out(rgb.width(), rgb.height());
  for (std::size_t i = 0; i < rgb.size(); ++i) out[i] = Luminance(rgb[i]);
  return out;
}

}  // namespace hdrf::eval
