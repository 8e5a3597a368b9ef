// Project files (.hdrproj): chunks, manifest, model, keyframes, relocaliser codes; a project
// that loads is also turned back into a scan session, as --resume does.
#include "fuzz_support.h"
#include "io/project.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "scan.hdrproj");
  hdrf::fuzz::Expect([&] {
    const hdrf::io::Project p = hdrf::io::LoadProject(file);
    hdrf::io::ResumeSession(p, [](hdrf::pipeline::PipelineOptions&) {});
  });
  return 0;
}
