// The test OpenNI2 device's environment for a test program: a private folder with the hot-plug
// control file and the profile folder (XDG_DATA_HOME), set before OpenNI2 loads the driver
// (it reads them once), removed at exit. The control file's words: plugged or unplugged, then
// optionally "still" (the camera holds its view) and "light=F" (docs/sensors.md).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace hdrf::test {

class TestDeviceControl {
 public:
  TestDeviceControl(const std::string& name, const std::string& words) {
    root_ = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(getpid()));
    std::filesystem::create_directories(root_ / "xdg");
    control_ = root_ / "control";
    std::ofstream(control_) << words << "\n";
    setenv("HDRF_TEST_DEVICE_CONTROL", control_.c_str(), 1);
    setenv("XDG_DATA_HOME", (root_ / "xdg").c_str(), 1);
  }
  ~TestDeviceControl() {
    std::error_code ec;
    std::filesystem::remove_all(root_, ec);
  }
  TestDeviceControl(const TestDeviceControl&) = delete;
  TestDeviceControl& operator=(const TestDeviceControl&) = delete;

  // Writes the control file; with `settle`, waits for the driver's 10 ms poll to see it.
  void Set(const std::string& words, bool settle = true) const {
    std::ofstream(control_) << words << "\n";
    if (settle) usleep(100000);
  }
  void Plug(bool on) const { Set(on ? "plugged" : "unplugged", false); }
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_, control_;
};

}  // namespace hdrf::test
