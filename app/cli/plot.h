// Minimal line plots into an image, for calibration reports (no fonts: the report text says
// what the axes are).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/image.h"

namespace hdrf::cli {

class Plot {
 public:
  Plot(int width, int height, double x0, double x1, double y0, double y1)
      : img_(width, height, Rgb8{255, 255, 255}), x0_(x0), x1_(x1), y0_(y0), y1_(y1) {
    for (int k = 0; k <= 4; ++k) {  // grid at quarters, frame
      const int gx = Px(x0 + (x1 - x0) * k / 4.0), gy = Py(y0 + (y1 - y0) * k / 4.0);
      const Rgb8 c = (k == 0 || k == 4) ? Rgb8{0, 0, 0} : Rgb8{215, 215, 215};
      for (int y = kMargin; y <= height - kMargin; ++y) Set(gx, y, c);
      for (int x = kMargin; x <= width - kMargin; ++x) Set(x, gy, c);
    }
  }
  void Line(const std::vector<double>& xs, const std::vector<double>& ys, Rgb8 color, int thick = 2) {
    for (std::size_t i = 1; i < xs.size(); ++i) {
      const double ax = Px(xs[i - 1]), ay = Py(ys[i - 1]), bx = Px(xs[i]), by = Py(ys[i]);
      const int n = int(std::max(std::abs(bx - ax), std::abs(by - ay))) + 1;
      for (int k = 0; k <= n; ++k) {
        const int x = int(std::lround(ax + (bx - ax) * k / n)), y = int(std::lround(ay + (by - ay) * k / n));
        for (int dy = 0; dy < thick; ++dy)
          for (int dx = 0; dx < thick; ++dx) Set(x + dx, y + dy, color);
      }
    }
  }
  const ColorImage& image() const { return img_; }

 private:
  static constexpr int kMargin = 12;
  int Px(double x) const {
    return kMargin + int(std::lround((x - x0_) / (x1_ - x0_) * (img_.width() - 2 * kMargin)));
  }
  int Py(double y) const {
    const double t = std::clamp((y - y0_) / (y1_ - y0_), -0.02, 1.02);
    return img_.height() - kMargin - int(std::lround(t * (img_.height() - 2 * kMargin)));
  }
  void Set(int x, int y, Rgb8 c) {
    if (x >= 0 && y >= 0 && x < img_.width() && y < img_.height()) img_(x, y) = c;
  }
  ColorImage img_;
  double x0_, x1_, y0_, y1_;
};

inline const Rgb8 kChannelColor[3] = {{210, 40, 40}, {30, 150, 50}, {40, 70, 210}};

}  // namespace hdrf::cli
