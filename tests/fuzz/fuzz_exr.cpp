// OpenEXR radiance images (hdr/ frames, tonemap input): RGB, one channel, attributes.
#include "fuzz_support.h"
#include "io/exr.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "image.exr");
  hdrf::fuzz::Expect([&] { hdrf::io::ReadExr(file); });
  hdrf::fuzz::Expect([&] { hdrf::io::ReadExrChannel(file, "Z"); });
  hdrf::fuzz::Expect([&] { hdrf::io::ReadExrAttribute(file, "hdrfusion:units"); });
  return 0;
}
