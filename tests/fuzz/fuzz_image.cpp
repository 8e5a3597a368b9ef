// Frame images: colour (8-bit RGB) and depth (16-bit), PNG or anything OpenCV decodes.
#include "fuzz_support.h"
#include "common/error.h"
#include "io/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "frame.png");
  hdrf::fuzz::Expect([&] { hdrf::io::ReadColorImage(file); });
  hdrf::fuzz::Expect([&] { hdrf::io::ReadDepthImage(file, [](int w, int h) {
    if (w != 64 || h != 48) throw hdrf::Error("not the camera's size");
  }); });
  return 0;
}
