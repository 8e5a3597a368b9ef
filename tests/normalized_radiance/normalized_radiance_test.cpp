#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <utility>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "normalized_radiance/normalized_radiance.h"
#include "normalized_radiance/normalized_radiance_driver.h"
#include "radiometry/pcf.h"
#include "radiometry/radiance.h"
#include "sim/builtin_sensor.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

// One static view of the room at 4 ms and 32 ms (8x apart): colour, radiance, confidence.
struct TwoExposures {
  sim::SimFrame a, b;
  RadianceImage ra, rb;
  Image<float> ca, cb;
};
TwoExposures ViewAt4And32Ms() {
  sim::SimOptions o;
  o.sweep = true;
  o.sweep_exposures_ms = {4, 32};
  o.sweep_repeats = 1;
  sim::SyntheticSource src(o);
  TwoExposures v;
  v.a = src.Next();
  v.b = src.Next();
  const SensorInfo s = src.sensor();
  const radiometry::PcfTables pcf = radiometry::ComputePcf(*s.response, *s.noise);
  Image<float> ma, mb;
  radiometry::ConvertFrame(v.a.color, *s.response, pcf, 1, v.ra, v.ca, ma);
  radiometry::ConvertFrame(v.b.color, *s.response, pcf, 1, v.rb, v.cb, mb);
  return v;
}

TEST(NormalizedRadiance, IsExposureInvariant) {
  // One static view at 4 ms and 32 ms (8x apart).
  const TwoExposures v = ViewAt4And32Ms();
  const sim::SimFrame& a = v.a;
  const sim::SimFrame& b = v.b;
  const RadianceImage &ra = v.ra, &rb = v.rb;
  const Image<float> &ca = v.ca, &cb = v.cb;
  const Image<float> na = nr::NormalizedRadiance(nr::Luminance(ra), {});
  const Image<float> nb = nr::NormalizedRadiance(nr::Luminance(rb), {});
  std::vector<double> diff, mag;
  for (std::size_t i = 0; i < na.size(); ++i) {
    if (ca[i] < 0.3f || cb[i] < 0.3f) continue;  // both well exposed
    diff.push_back(std::abs(na[i] - nb[i]));
    mag.push_back(std::abs(na[i]));
  }
  ASSERT_GT(diff.size(), 5000u);
  std::printf("NR at 4 and 32 ms: median |difference| %.3f against median |NR| %.3f over %zu pixels\n",
              Median(diff), Median(mag), diff.size());
  EXPECT_LT(Median(diff), 0.1);
  EXPECT_GT(Median(mag), 0.3);  // the signal is real, not all zeros
  // Raw intensity is not invariant at all: the baseline's problem.
  double raw_diff = 0;
  for (std::size_t i = 0; i < a.color.size(); ++i) raw_diff += std::abs(a.color[i].g - b.color[i].g);
  EXPECT_GT(raw_diff / double(a.color.size()), 30.0);
}

// Pixels clipped at 255 move with the exposure, and where they have no depth (a window, an
// emitter) the model's ray cast has no radiance there at all: inside a patch's statistics
// they shift the live frame's normalized radiance of the unclipped pixels beside them, which
// the model's does not have, and the photometric term pulls the pose across their border.
// The tracker leaves them out of the live frame (TrackingLuminanceOf): then the unclipped
// pixels near them normalize as in the model. Here the model is the 4 ms view without the
// surfaces the 32 ms view clips (as if they were a window), the live frame the 32 ms view.
TEST(NormalizedRadiance, ClippedLivePixelsAreLeftOutOfTheStatistics) {
  const TwoExposures v = ViewAt4And32Ms();
  const sim::SimFrame& a = v.a;
  const sim::SimFrame& b = v.b;
  const RadianceImage &ra = v.ra, &rb = v.rb;
  const Image<float> &ca = v.ca, &cb = v.cb;
  const int w = ra.width(), h = ra.height();
  Image<float> model = nr::Luminance(ra);
  long clipped = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (nr::PixelClipped(b.color(x, y))) model(x, y) = 0.f, ++clipped;
  const Image<float> nm = nr::NormalizedRadiance(model, {});
  const Image<float> plain = nr::NormalizedRadiance(nr::Luminance(rb), {});
  Image<float> lb(w, h), wb(w, h);
  nr::TrackingLuminanceOf(par::Host{}, View(b.color), View(rb), View(cb), View(lb), View(wb));
  const Image<float> left_out = nr::NormalizedRadiance(lb, {});
  // The unclipped, well-exposed pixels within 12 pixels of a clipped one.
  std::vector<double> d_plain, d_left_out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (nr::PixelClipped(b.color(x, y))) {
        ASSERT_EQ(lb(x, y), 0.f);  // no data, no weight, no NR
        ASSERT_EQ(wb(x, y), 0.f);
        ASSERT_EQ(left_out(x, y), 0.f);
        continue;
      }
      EXPECT_EQ(wb(x, y), cb(x, y));  // an unclipped pixel keeps its confidence
      if (ca(x, y) < 0.3f || cb(x, y) < 0.3f) continue;
      bool near = false;
      for (int dy = -12; dy <= 12 && !near; ++dy)
        for (int dx = -12; dx <= 12 && !near; ++dx) {
          const int xx = x + dx, yy = y + dy;
          near = xx >= 0 && yy >= 0 && xx < w && yy < h && nr::PixelClipped(b.color(xx, yy));
        }
      if (!near) continue;
      d_plain.push_back(std::abs(nm(x, y) - plain(x, y)));
      d_left_out.push_back(std::abs(nm(x, y) - left_out(x, y)));
    }
  std::printf("32 ms view: %ld clipped pixels; %zu unclipped pixels beside them: median |NR difference| from the "
              "model %.3f with the clipped pixels in the live statistics, %.3f with them left out\n",
              clipped, d_plain.size(), Median(d_plain), Median(d_left_out));
  ASSERT_GT(clipped, 500);
  ASSERT_GT(d_plain.size(), 500u);
  EXPECT_LT(Median(d_left_out), 0.1);
  EXPECT_LT(Median(d_left_out), 0.5 * Median(d_plain));
}

}  // namespace
}  // namespace hdrf

namespace hdrf::nr {
namespace {

// The per-pixel steps against brute force on a small image: cell means skip pixels without
// data, the integral images sum every cell above and left, the local statistics are the
// patch's mean and std, and a pixel normalizes by them (with the floor on flat patches).
TEST(NormalizedRadianceSteps, MatchBruteForceOnASmallImage) {
  Image<float> lum(6, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) lum(x, y) = float(1 + x + 3 * y);
  lum(0, 0) = 0;  // no data
  EXPECT_FLOAT_EQ(NrCellMean(View(lum), 0, 0, 2), (2.f + 4.f + 5.f) / 3.f);
  EXPECT_FLOAT_EQ(NrCellMean(View(lum), 2, 1, 2), 13.f);  // 11, 12, 14, 15
  Image<float> cells(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) cells(x, y) = NrCellMean(View(lum), x, y, 2);
  Image<double> cnt(4, 3), s1(4, 3), s2(4, 3);
  const NrIntegrals in{View(cnt), View(s1), View(s2)};
  for (int y = 0; y < 2; ++y) NrRowPass(View(cells), in, y);
  for (int x = 0; x <= 3; ++x) NrColumnPass(in, x);
  double all = 0, all2 = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) all += cells[i], all2 += double(cells[i]) * cells[i];
  EXPECT_DOUBLE_EQ(cnt(3, 2), 6.0);
  EXPECT_NEAR(s1(3, 2), all, 1e-9);
  EXPECT_NEAR(s2(3, 2), all2, 1e-6);
  float mean = 0, sd = 0;
  NrLocalStats(in, 1, 0, 2, &mean, &sd);  // a patch covering every cell
  const double m = all / 6, var = all2 / 6 - m * m;
  EXPECT_NEAR(mean, m, 1e-5);
  EXPECT_NEAR(sd, std::sqrt(var), 1e-4);
  // A pixel at the mean normalizes to 0; where the std is below the floor, the floor divides.
  Image<float> ms(1, 1, 10.f), ss(1, 1, 2.f), flat(1, 1, 0.f), one(2, 2, 14.f);
  float v = 0;
  NrPixel(View(one), View(ms), View(ss), 2, 1e-3f, 0, 0, &v, nullptr, nullptr);
  EXPECT_FLOAT_EQ(v, 2.f);
  NrPixel(View(one), View(ms), View(flat), 2, 0.1f, 0, 0, &v, nullptr, nullptr);
  EXPECT_FLOAT_EQ(v, 4.f);  // (14 - 10) / (0.1 * 10)
}

// The integral images on grids wider and taller than the passes' read-ahead (with a part
// chunk at each end): every entry is the running sums written out (along the row, then
// down the column, in that order), bit for bit; cells without data (0) are not counted.
TEST(NormalizedRadianceSteps, IntegralImagesAreTheRunningSumsInOrder) {
  for (const auto [w, h] : {std::pair{37, 29}, std::pair{8, 9}, std::pair{1, 17}, std::pair{16, 1}}) {
    Image<float> cells(w, h);
    std::uint32_t state = 99u + std::uint32_t(w * 131 + h);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      state = state * 1664525u + 1013904223u;
      cells[i] = (state >> 28) == 0 ? 0.f : float(state >> 8) / float(1u << 24) * 7.f;  // some without data
    }
    Image<double> cnt(w + 1, h + 1), s1(w + 1, h + 1), s2(w + 1, h + 1);
    const NrIntegrals in{View(cnt), View(s1), View(s2)};
    for (int y = 0; y < h; ++y) NrRowPass(View(cells), in, y);
    for (int x = 0; x <= w; ++x) NrColumnPass(in, x);
    long differ = 0;
    for (int X = 0; X <= w; ++X)
      for (int Y = 0; Y <= h; ++Y) {
        double c = 0, a = 0, b = 0;
        for (int y = 0; y < Y; ++y) {
          double rc = 0, ra = 0, rb = 0;
          for (int x = 0; x < X; ++x) {
            const double v = cells(x, y);
            rc += v > 0 ? 1.0 : 0.0;
            ra += v;
            rb += v * v;
          }
          c += rc, a += ra, b += rb;
        }
        differ += cnt(X, Y) != c || s1(X, Y) != a || s2(X, Y) != b;
      }
    EXPECT_EQ(differ, 0) << w << "x" << h;
  }
}

}  // namespace
}  // namespace hdrf::nr
