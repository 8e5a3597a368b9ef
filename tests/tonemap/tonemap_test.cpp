// The one Reinhard definition (core/tonemap) that the reports, the PLY colours and the
// studio's views share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <cstdio>
#include <limits>
#include <vector>

#include "tonemap/display.h"
#include "common/error.h"
#include "tonemap/mantiuk06/mantiuk06.h"
#include "tonemap/operator.h"

namespace hdrf::tonemap {
namespace {

TEST(Reinhard, PixelCurveAndLogAverage) {
  const Float3 grey = ReinhardPixel({1.f, 1.f, 1.f});  // luminance 1 -> 1 / (1 + 1)
  EXPECT_NEAR(grey.x, 0.5f, 1e-6);
  EXPECT_NEAR(grey.z, 0.5f, 1e-6);
  const Float3 red = ReinhardPixel({3.f, 0.f, 0.f});  // colour ratios kept
  EXPECT_EQ(red.y, 0.f);
  EXPECT_NEAR(red.x, 3.f / (1.f + 3.f * 0.2126f), 1e-5);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(ReinhardPixel({nan, 1.f, 1.f}).y, 0.f);
  EXPECT_EQ(ReinhardPixel({-1.f, -1.f, -1.f}).x, 0.f);
  const std::vector<Float3> px = {{0, 0, 0}, {4, 4, 4}, {0.25f, 0.25f, 0.25f}, {nan, nan, nan}};
  EXPECT_NEAR(LogAverageLuminance(px.data(), px.size()), 1.f, 1e-5);  // sqrt(4 * 0.25); the rest left out
  EXPECT_EQ(LogAverageLuminance(px.data(), 1), 1.f);                   // none usable
  // The image operator maps the log-average to the key: a uniform image at any level gives
  // the same display value.
  RadianceImage dim(2, 2, Float3{0.01f, 0.01f, 0.01f}), bright(2, 2, Float3{50.f, 50.f, 50.f});
  EXPECT_EQ(Reinhard(dim)[0].r, Reinhard(bright)[0].r);
}

// A view made of a textured dark surface and a textured bright one, `bright_share` of its
// columns bright (the camera turning from the dark to the bright).
RadianceImage TwoSurfaces(double bright_share) {
  RadianceImage r(64, 48);
  for (int y = 0; y < r.height(); ++y)
    for (int x = 0; x < r.width(); ++x) {
      const float texture = 1.f + 0.5f * float(((x / 3) + (y / 3)) % 2);
      const float level = x < bright_share * r.width() ? 40.f : 0.2f;
      r(x, y) = Float3{1, 1, 1} * level * texture;
    }
  return r;
}

// Mean log10 display luminance (display-linear output through the default LCD model).
double ShownMeanLog(const Image<Float3>& out) {
  double s = 0;
  for (std::size_t i = 0; i < out.size(); ++i) s += std::log10(Luminance(out[i]) * (200 - 0.8) + 0.8 + 0.6 / 3.14159265);
  return s / double(out.size());
}

// mantiuk08's brightness hold: when the view turns to brighter surfaces the frame's own curve
// changes the shown brightness at once; the hold keeps it (within its stops) and then lets it
// follow at its pace; stills are not held; the mesh (MapList) gets the curve without it.
TEST(Mantiuk08, BrightnessHoldSteadiesAViewThatTurnsAndThenAdapts) {
  const OperatorDecl& d = FindOperator("mantiuk08");
  const std::vector<Float3> vertices = {{0.2f, 0.2f, 0.2f}, {40.f, 40.f, 40.f}, {3.f, 2.f, 1.f}};
  struct Turn {
    double jump_held = 0, jump_free = 0, last_held = 0, last_free = 0;
  };
  // A minute at 30 frames/s, turning at 2 s from `from` to `to` of the view bright; the
  // largest change of the shown brightness in the half second after the turn, and the last.
  auto turn = [&](double from, double to) {
    auto held = d.make(ResolveParams(d, {}), Device::kCpu);
    auto free = d.make(ResolveParams(d, {{"hold", 0}}), Device::kCpu);
    Image<Float3> a, b;
    Turn r;
    double before_h = 0, before_f = 0, t = 0;
    for (int i = 0; i < 30 * 60; ++i, t += 1.0 / 30) {
      const RadianceImage view = TwoSurfaces(i < 60 ? from : to);
      held->Map(view, a, {t});
      free->Map(view, b, {t});
      const double mh = ShownMeanLog(a), mf = ShownMeanLog(b);
      if (i == 59) before_h = mh, before_f = mf;
      if (i >= 60 && i < 75)
        r.jump_held = std::max(r.jump_held, std::abs(mh - before_h)), r.jump_free = std::max(r.jump_free, std::abs(mf - before_f));
      r.last_held = mh, r.last_free = mf;
      // The 3-D view's colours do not carry the hold.
      const auto lh = held->MapList(vertices), lf = free->MapList(vertices);
      for (std::size_t k = 0; k < vertices.size(); ++k) EXPECT_NEAR(lh[k].y, lf[k].y, 1e-6) << "frame " << i;
    }
    std::printf("view from %.0f %% to %.0f %% bright: shown mean log10 luminance moved by %.3f held, %.3f without the "
                "hold in the half second after the turn\n",
                100 * from, 100 * to, r.jump_held, r.jump_free);
    return r;
  };
  const double two_stops = 2 * std::log10(2.0);
  const Turn small = turn(0.3, 0.45);
  EXPECT_GT(small.jump_free, 0.1);                   // the frame's own curve changes the brightness
  EXPECT_LT(small.jump_held, 0.25 * small.jump_free);  // held
  EXPECT_NEAR(small.last_held, small.last_free, 0.01);  // adapted after a minute
  const Turn large = turn(0.2, 0.8);  // more than the hold keeps: it gives way by the excess
  EXPECT_GT(large.jump_free, two_stops + 0.2);
  EXPECT_GT(large.jump_held, large.jump_free - two_stops - 0.05);  // never more than two stops held
  EXPECT_LT(large.jump_held, large.jump_free - two_stops + 0.1);   // (less where the display range clips)
  EXPECT_NEAR(large.last_held, large.last_free, 0.01);
  // A still is never held: the same image gives the same result with and without the hold.
  auto held = d.make(ResolveParams(d, {}), Device::kCpu);
  auto free = d.make(ResolveParams(d, {{"hold", 0}}), Device::kCpu);
  Image<Float3> a, b;
  held->Map(TwoSurfaces(0.2), a, FrameTime::Still());
  free->Map(TwoSurfaces(0.2), b, FrameTime::Still());
  EXPECT_NEAR(ShownMeanLog(a), ShownMeanLog(b), 1e-9);
  EXPECT_THROW(d.make(ResolveParams(d, {{"hold_hz", 0}}), Device::kCpu), SettingError);
}

}  // namespace
}  // namespace hdrf::tonemap

namespace hdrf::tonemap {
namespace {

// A uniform image has no contrast to map: mantiuk06 shows it as one grey (the middle of the
// display's range), on every size, instead of stretching the solver's rounding across the
// display as bands.
TEST(Mantiuk06, AUniformImageIsShownAsOneMidGrey) {
  for (auto [w, h] : {std::pair{64, 48}, {640, 480}, {333, 211}}) {
    RadianceImage in(w, h);
    for (std::size_t i = 0; i < in.size(); ++i) in[i] = {0.21f, 0.21f, 0.21f};
    Image<Float3> out(w, h);
    m06::Map(in, out, m06::Options{});
    float lo = 1e30f, hi = -1e30f;
    for (std::size_t i = 0; i < out.size(); ++i) lo = std::min(lo, out[i].y), hi = std::max(hi, out[i].y);
    EXPECT_LE(hi - lo, 1e-4f) << w << "x" << h << ": " << lo << " .. " << hi;
    EXPECT_NEAR(std::log10(hi), -1.15, 0.05) << w << "x" << h;  // half the display's 2.3 log10 units
  }
}

}  // namespace
}  // namespace hdrf::tonemap
