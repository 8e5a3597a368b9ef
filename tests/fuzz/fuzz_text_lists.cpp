// Sequence lists (rgb.txt, depth.txt), exposure.txt and TUM trajectories: one input, read
// by each of the four text-table readers.
#include "fuzz_support.h"
#include "io/tum.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "list.txt");
  hdrf::fuzz::Expect([&] { hdrf::io::ReadImageList(file); });
  hdrf::fuzz::Expect([&] { hdrf::io::ReadExposures(file); });
  hdrf::fuzz::Expect([&] { hdrf::io::ReadTrajectory(file); });
  return 0;
}
