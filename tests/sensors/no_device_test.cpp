// No camera and no test driver (a private OpenNI2 with only the file player): listing says
// none, opening fails with a message, and the CLI says so with the right exit status.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "sensors/live_source.h"
#include "sensors/openni_camera.h"

namespace {

struct CliRun {
  int status;
  std::string output;
};
CliRun Cli(const std::string& args) {
  const std::string cmd = std::string("LD_LIBRARY_PATH=") + HDRF_OPENNI_EMPTY_DIR + " " + HDRF_CLI + " " + args + " 2>&1";
  CliRun r{0, ""};
  FILE* p = popen(cmd.c_str(), "r");
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) r.output += buf;
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

TEST(NoDevice, ListIsEmptyAndOpenSaysWhy) {
  EXPECT_TRUE(hdrf::sensors::ListDevices().empty());
  try {
    hdrf::sensors::OpenNiCamera::Open("", {});
    FAIL() << "opening with no device succeeded";
  } catch (const hdrf::sensors::SensorError& e) {
    EXPECT_NE(std::string(e.what()).find("no OpenNI2 device is connected"), std::string::npos) << e.what();
  }
}

TEST(NoDevice, CliSensorsRecordAndLiveScan) {
  const CliRun list = Cli("sensors");
  EXPECT_EQ(list.status, 0) << list.output;
  EXPECT_NE(list.output.find("no OpenNI2 device is connected"), std::string::npos) << list.output;

  const std::string out = testing::TempDir() + "/hdrf_none_rec";
  const CliRun rec = Cli("record --out " + out + " --frames 10");
  EXPECT_EQ(rec.status, 1) << rec.output;
  EXPECT_NE(rec.output.find("no OpenNI2 device is connected"), std::string::npos) << rec.output;

  const CliRun scan = Cli("scan openni:frames=10 --out " + testing::TempDir() + "/hdrf_none_scan");
  EXPECT_EQ(scan.status, 1) << scan.output;
  EXPECT_NE(scan.output.find("no OpenNI2 device is connected"), std::string::npos) << scan.output;
}

TEST(NoDevice, BadLiveSpecsNameTheKey) {
  using hdrf::sensors::ParseLiveSpec;
  EXPECT_THROW(ParseLiveSpec("openni:mode=hd"), hdrf::SettingError);
  EXPECT_THROW(ParseLiveSpec("openni:exposure=-3"), hdrf::SettingError);
  EXPECT_THROW(ParseLiveSpec("openni:exposure=10,ae=on"), hdrf::SettingError);
  EXPECT_THROW(ParseLiveSpec("openni:frames=0"), hdrf::SettingError);
  EXPECT_THROW(ParseLiveSpec("openni:colour=1"), hdrf::SettingError);
  const auto o = ParseLiveSpec("openni:device=ABC,mode=qvga,exposure=12.5,gain=200,frames=7");
  EXPECT_EQ(o.device, "ABC");
  EXPECT_EQ(o.mode.width, 320);
  EXPECT_DOUBLE_EQ(*o.exposure_ms, 12.5);
  EXPECT_FALSE(*o.auto_exposure);
  EXPECT_EQ(*o.gain, 200);
  EXPECT_EQ(o.frames, 7);
}

}  // namespace
