#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "common/lanes.h"
#include "common/vec.h"

namespace hdrf {
namespace {

// The four-lane rounding the host's vector loops use gives RoundToInt's integer in every lane:
// halves (away from zero), values just either side of them, negatives, the int range's edges,
// infinities and NaN, and a sweep of floats' bit patterns.
TEST(Lanes, RoundToIntLanesIsRoundToIntInEveryLane) {
  std::vector<float> x = {0.f, -0.f, 0.5f, -0.5f, 1.5f, -1.5f, 2.5f, -2.5f, 0.49999997f, -0.49999997f,
                          std::nextafter(0.5f, 1.f), std::nextafter(-0.5f, -1.f), 319.5f, 639.49997f, -1e-30f,
                          8388607.5f, 8388608.f, 2147483520.f, -2147483520.f, 2147483392.f, -2147483648.f, 3e9f, -3e9f,
                          std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                          std::numeric_limits<float>::quiet_NaN()};
  for (std::uint32_t bits = 0; bits < 0xffffffffu - 40000u; bits += 40009u) {  // every sign, exponent
    float f;
    std::memcpy(&f, &bits, sizeof f);
    x.push_back(f);
  }
  while (x.size() % 4) x.push_back(0.25f);
  int checked = 0, halves = 0;
  for (std::size_t i = 0; i < x.size(); i += 4) {
    const Lanes v = {x[i], x[i + 1], x[i + 2], x[i + 3]};
    const LaneInts r = RoundToIntLanes(v);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(r[k], RoundToInt(x[i + std::size_t(k)])) << "x = " << x[i + std::size_t(k)];
      ++checked;
      halves += std::fabs(x[i + std::size_t(k)] - std::trunc(x[i + std::size_t(k)])) == 0.5f;
    }
  }
  EXPECT_GT(checked, 100000);
  EXPECT_GE(halves, 8);
}

}  // namespace
}  // namespace hdrf
