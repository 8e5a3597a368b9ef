// CPU against CUDA on identical inputs. Skips (with the reason) where no GPU is usable.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/cuda_runtime.h"
#include "radiometry/radiance.h"

namespace hdrf::radiometry {
namespace {

// An Xtion-like inverse response: steep at the top, not a gamma (values only need to be
// realistic and monotonic for parity).
InverseResponse TestResponse() {
  InverseResponse r;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) {
      const double x = i / 255.0;
      r.table[c][i] = float(0.03 * (c + 1) + std::pow(x, 2.2 + 0.1 * c) * 12.0 +
                            0.5 * std::exp(8.0 * (x - 1.0)) * 7.0);
    }
  return r;
}

TEST(GpuParity, RadianceConversionMatchesCpu) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
  std::printf("GPU: %s\n", CudaDeviceDescription().c_str());
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> level(0, 255);
  ColorImage img(640, 480);
  for (std::size_t i = 0; i < img.size(); ++i)
    img[i] = {std::uint8_t(level(rng)), std::uint8_t(level(rng)), std::uint8_t(level(rng))};
  const InverseResponse r = TestResponse();
  RadianceImage cpu, gpu;
  ConvertToRadiance(img, r, 12.5f, cpu, Device::kCpu);
  ConvertToRadiance(img, r, 12.5f, gpu, Device::kCuda);
  ASSERT_EQ(cpu.size(), gpu.size());
  double worst_rel = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    const float a[3] = {cpu[i].x, cpu[i].y, cpu[i].z};
    const float b[3] = {gpu[i].x, gpu[i].y, gpu[i].z};
    for (int c = 0; c < 3; ++c)
      worst_rel = std::max(worst_rel, std::abs(double(a[c]) - b[c]) / std::max(1e-12, double(a[c])));
  }
  std::printf("radiance parity: %zu pixels, max relative difference %.3g\n", cpu.size(),
              worst_rel);
  EXPECT_LE(worst_rel, 1e-6);
}

}  // namespace
}  // namespace hdrf::radiometry

#include "radiometry/pcf.h"
#include "sim/builtin_sensor.h"

namespace hdrf::radiometry {
namespace {

TEST(GpuParity, FrameConversionRadianceAndConfidenceMatchCpu) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
  const SensorInfo s = sim::BuiltinXtionProfile();
  const radiometry::PcfTables pcf = radiometry::ComputePcf(*s.response, *s.noise);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> level(0, 255);
  ColorImage img(320, 240);
  for (std::size_t i = 0; i < img.size(); ++i)
    img[i] = {std::uint8_t(level(rng)), std::uint8_t(level(rng)), std::uint8_t(level(rng))};
  for (int k = 0; k <= 3; ++k) {
    RadianceImage rc, rg;
    Image<float> cc, cg, mc, mg;
    ConvertFrame(img, *s.response, pcf, k, rc, cc, mc, Device::kCpu);
    ConvertFrame(img, *s.response, pcf, k, rg, cg, mg, Device::kCuda);
    double worst = 0;
    for (std::size_t i = 0; i < img.size(); ++i) {
      worst = std::max(worst, double(std::abs(rc[i].x - rg[i].x) + std::abs(rc[i].y - rg[i].y) +
                                     std::abs(rc[i].z - rg[i].z)));
      worst = std::max(worst, double(std::abs(cc[i] - cg[i]) + std::abs(mc[i] - mg[i])));
    }
    std::printf("frame conversion parity, PCF p%d: max absolute difference %.3g\n", k, worst);
    EXPECT_LE(worst, 1e-6);
  }
}

}  // namespace
}  // namespace hdrf::radiometry
