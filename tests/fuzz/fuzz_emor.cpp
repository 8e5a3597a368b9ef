// EMoR basis files (invemor.txt, `calibrate --method emor --emor-basis`): a basis that loads
// must hold only finite values (a non-finite one would reach the fit as NaN).
#include <cmath>
#include <cstdlib>

#include "fuzz_support.h"
#include "radiometry/calibration.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = hdrf::fuzz::AsFile(data, size, "invemor.txt");
  hdrf::fuzz::Expect([&] {
    const hdrf::radiometry::EmorBasis b = hdrf::radiometry::EmorBasis::Load(file);
    for (double v : b.g0)
      if (!std::isfinite(v)) std::abort();
    for (const auto& h : b.h)
      for (double v : h)
        if (!std::isfinite(v)) std::abort();
  });
  return 0;
}
