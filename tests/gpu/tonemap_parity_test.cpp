// The tone-mapping operators on the CPU and on CUDA, same input: a synthetic HDR frame (the
// desk scene's true radiance at 640x480, over three decades) with holes of no data. Skips
// (with the reason) where no GPU is usable.
#include <gtest/gtest.h>

#include <cmath>

#include "common/cuda_runtime.h"
#include "eval/image_quality.h"
#include "sim/synthetic_source.h"
#include "tonemap/mantiuk06/mantiuk06.h"
#include "tonemap/mantiuk08/mantiuk08.h"
#include "tonemap/operator.h"

namespace hdrf::tonemap {
namespace {

RadianceImage TestFrame() {
  sim::SimOptions o;
  o.scene = "desk";
  o.width = 640, o.height = 480;
  o.frames = 1;
  sim::SyntheticSource src(o);
  RadianceImage r = src.Next().radiance;
  for (int y = 100; y < 140; ++y)
    for (int x = 200; x < 260; ++x) r(x, y) = {0, 0, 0};  // a hole with no data
  return r;
}

double MaxDifference(const Image<Float3>& a, const Image<Float3>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max({worst, double(std::abs(a[i].x - b[i].x)), double(std::abs(a[i].y - b[i].y)),
                      double(std::abs(a[i].z - b[i].z))});
  return worst;
}

TEST(GpuParity, Mantiuk08DensityCurveAndImageMatchCpu) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
  const RadianceImage r = TestFrame();
  const float floor = m08::LuminanceFloor(r);
  const int bands = m08::BandCount(30);
  const m08::Density cpu = m08::ComputeDensity(r, floor, bands);
  m08::CudaWorkspace ws;
  ws.Upload(r);
  const m08::Density gpu = ws.ComputeDensity(floor, bands);
  ASSERT_EQ(cpu.count.size(), gpu.count.size());
  double moved = 0;
  for (std::size_t i = 0; i < cpu.count.size(); ++i) moved += std::abs(cpu.count[i] - gpu.count[i]);
  const m08::Options o;
  const m08::ToneCurve yc = m08::OptimiseCurve(cpu, o), yg = m08::OptimiseCurve(gpu, o);
  double curve = 0;
  for (int i = 0; i < m08::kNodes; ++i) curve = std::max(curve, std::abs(yc[std::size_t(i)] - yg[std::size_t(i)]));
  const m08::CurveLut lut = m08::MakeLut(yc, o, floor);
  Image<Float3> out_gpu;
  ws.Apply(lut, out_gpu);
  const auto& d = FindOperator("mantiuk08");
  Image<Float3> op_cpu, op_gpu;
  d.make(ResolveParams(d, {}), Device::kCpu)->Map(r, op_cpu, FrameTime::Still());
  d.make(ResolveParams(d, {}), Device::kCuda)->Map(r, op_gpu, FrameTime::Still());
  const double image = MaxDifference(op_cpu, op_gpu);
  std::printf("mantiuk08 parity: %.0f of %.0f counts in another cell, curve max %.2g log10, image max %.2g\n", moved / 2,
              cpu.total, curve, image);
  EXPECT_LE(moved / 2, 1e-4 * cpu.total);  // log10 may round differently at a bin edge
  EXPECT_LE(curve, 1e-3);
  EXPECT_LE(image, 2e-3);
  EXPECT_EQ(out_gpu(220, 120).x, 0.f);  // no data stays black
}

TEST(GpuParity, Mantiuk06ImageMatchesCpu) {
  std::string why;
  if (!CudaAvailable(&why)) GTEST_SKIP() << "CUDA not usable here: " << why;
  const RadianceImage r = TestFrame();
  for (const bool eq : {false, true}) {
    m06::Options o;
    o.equalise = eq;
    o.contrast = eq ? 0.5 : 0.1;
    Image<Float3> cpu, gpu;
    const m06::Result rc = m06::Map(r, cpu, o);
    const m06::Result rg = m06::MapCuda(r, gpu, o);
    const double ssim = eval::Ssim(eval::LuminanceOf(cpu), eval::LuminanceOf(gpu));
    const double worst = MaxDifference(cpu, gpu);
    std::printf("mantiuk06 parity (%s): CPU %d iterations residual %.2g, CUDA %d residual %.2g; SSIM %.5f, max %.3g\n",
                eq ? "equalisation" : "mapping", rc.iterations, rc.residual, rg.iterations, rg.residual, ssim, worst);
    EXPECT_GE(ssim, 0.999);
    EXPECT_LE(worst, 0.02);
    EXPECT_EQ(gpu(220, 120).x, 0.f);
  }
}

}  // namespace
}  // namespace hdrf::tonemap
