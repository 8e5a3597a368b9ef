#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine_bench.h"

namespace hdrf::pipeline {
namespace {

// A GPU row whose floors are known: 1 GB/s, so each stage's floor in ms is its bytes / 1e6.
EngineBenchRow GpuRow(int width, int height) {
  EngineBenchRow r;
  r.device = Device::kCuda;
  r.c.width = width;
  r.c.height = height;
  r.bandwidth = 1e9;
  r.bytes.convert = 3000;     // floor 0.003 ms: 5x = 0.015
  r.bytes.normalize = 1000;   // 0.001: 5x = 0.005
  r.bytes.track = 2500;       // 0.0025: 5x = 0.0125
  r.bytes.integrate = 2000;   // 0.002: 5x = 0.010
  r.bytes.raycast = 20000;    // 0.02: 5x = 0.1
  r.ms.convert = 0.2;
  r.least_stage_ms = {0.010, 0.012, 0.016, 0.024};
  return r;
}

std::string LineOf(const std::string& table, const std::string& start) {
  const std::size_t at = table.find(start);
  if (at == std::string::npos) return "";
  return table.substr(at, table.find('\n', at) - at);
}

// How many launches fit in five times a stage's floor: the most of 1, 2, 4, 8 whose least time
// is at most that, 0 where not even one does.
TEST(EngineBench, LeastStageTableCountsTheLaunchesThatFitInFiveFloors) {
  const std::string t = EngineLeastStageTable({GpuRow(64, 48)});
  ASSERT_FALSE(t.empty());
  EXPECT_NE(t.find("0.0100, 0.0120, 0.0160, 0.0240 ms"), std::string::npos) << t;
  EXPECT_EQ(LineOf(t, "| cuda | compact | 64x48 | convert |"), "| cuda | compact | 64x48 | convert | 0.200 | 0.0150 | 2 |");
  EXPECT_EQ(LineOf(t, "| cuda | compact | 64x48 | normalize |"), "| cuda | compact | 64x48 | normalize | 0.000 | 0.0050 | 0 |");
  EXPECT_EQ(LineOf(t, "| cuda | compact | 64x48 | track |"), "| cuda | compact | 64x48 | track | 0.000 | 0.0125 | 2 |");
  EXPECT_EQ(LineOf(t, "| cuda | compact | 64x48 | integrate |"), "| cuda | compact | 64x48 | integrate | 0.000 | 0.0100 | 1 |");
  EXPECT_EQ(LineOf(t, "| cuda | compact | 64x48 | raycast |"), "| cuda | compact | 64x48 | raycast | 0.000 | 0.1000 | 8 or more |");
}

// Only GPU rows have the table (the CPU's stages wait for no device): none, no table.
TEST(EngineBench, LeastStageTableHasOnlyTheGpuRows) {
  EngineBenchRow cpu = GpuRow(32, 24);
  cpu.device = Device::kCpu;
  cpu.least_stage_ms = {};
  EXPECT_EQ(EngineLeastStageTable({cpu}), "");
  const std::string t = EngineLeastStageTable({cpu, GpuRow(64, 48)});
  EXPECT_EQ(t.find("| cpu |"), std::string::npos) << t;
  EXPECT_NE(t.find("| cuda | compact | 64x48 | raycast |"), std::string::npos) << t;
}

}  // namespace
}  // namespace hdrf::pipeline
