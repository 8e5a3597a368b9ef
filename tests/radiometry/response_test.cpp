#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "radiometry/response.h"
#include "support/test_support.h"

namespace hdrf::radiometry {
namespace {

InverseResponse Linear() {
  InverseResponse r;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) r.table[c][i] = float(i) / 255.f;
  return r;
}

TEST(InverseResponse, AcceptsMonotonicTables) {
  EXPECT_NO_THROW(Linear().Check("test"));
  EXPECT_NO_THROW(InverseResponse::Srgb().Check("srgb"));
}

TEST(InverseResponse, RejectsDecreasingStepNamingChannelAndLevel) {
  InverseResponse r = Linear();
  r.table[1][100] = r.table[1][98];
  test::ExpectErrorContaining([&] { r.Check("cam.json"); },
                              {"cam.json", "channel g", "level 100", "monotonic"});
}

TEST(InverseResponse, RejectsNaNAndNegative) {
  InverseResponse r = Linear();
  r.table[2][7] = std::nanf("");
  test::ExpectErrorContaining([&] { r.Check("x.json"); }, {"x.json", "channel b", "level 7"});
  r = Linear();
  r.table[0][0] = -0.5f;
  test::ExpectErrorContaining([&] { r.Check("x.json"); }, {"negative"});
}

TEST(InverseResponse, SrgbFallbackHasKnownValues) {
  const InverseResponse s = InverseResponse::Srgb();
  EXPECT_FLOAT_EQ(s.table[0][255], 1.0f);
  EXPECT_FLOAT_EQ(s.table[0][0], 0.0f);
  EXPECT_NEAR(s.table[1][128], 0.21586f, 1e-4);  // sRGB 128/255 -> linear 0.2159
  EXPECT_NEAR(s.table[2][10], 10.0f / 255.0f / 12.92f, 1e-7);
}

TEST(NoiseModel, RejectsNegativeSigma) {
  NoiseModel n;
  n.sigma_s = {0.01f, 0.02f, 0.03f};
  n.sigma_c = {0.0f, -1.0f, 0.0f};
  test::ExpectErrorContaining([&] { n.Check("s.json"); }, {"s.json", "channel g"});
}

}  // namespace
}  // namespace hdrf::radiometry
