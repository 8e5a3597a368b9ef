// Engine settings files (--options): every key through the options registry, then the
// whole set checked as a scan would.
#include "fuzz_support.h"
#include "io/options_json.h"
#include "pipeline/pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "options.json");
  hdrf::fuzz::Expect([&] {
    hdrf::pipeline::PipelineOptions o;
    hdrf::io::ReadPipelineOptions(file, o);
    o.Check();
  });
  return 0;
}
