// sensor.json: intrinsics, depth scale, response, noise, device block.
#include "fuzz_support.h"
#include "io/sensor_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "sensor.json");
  hdrf::fuzz::Expect([&] { hdrf::io::ReadSensorJson(file); });
  return 0;
}
