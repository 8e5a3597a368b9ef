// HDR meshes (PLY with radiance), as export reads them.
#include "fuzz_support.h"
#include "io/ply.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "mesh.ply");
  std::vector<std::uint8_t> flags;
  hdrf::fuzz::Expect([&] { hdrf::io::ReadPly(file, &flags); });
  return 0;
}
