#include "radiometry/radiance.h"
#include "radiometry/radiance_impl.h"

namespace hdrf::radiometry::detail {

void ConvertToRadianceCpu(const ColorImage& color, const float* inv_tables, float inv_exposure,
                          RadianceImage& out) {
  const long n = long(color.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) out[i] = PixelRadiance(color[i], inv_tables, inv_exposure);
}

}  // namespace hdrf::radiometry::detail
