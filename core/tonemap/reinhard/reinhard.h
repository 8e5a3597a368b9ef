// Reinhard et al. 2002, the global photographic operator: the image is scaled so that its
// log-average luminance maps to a key, then each pixel's luminance L goes to L / (1 + L),
// colour ratios kept. The one implementation the reports, the PLY colours, the CLI and the
// studio share.
#pragma once

#include <cmath>

#include "common/host_device.h"
#include "common/vec.h"
#include "tonemap/operator.h"

namespace hdrf::tonemap {

// Reinhard's curve on one pixel already scaled by the exposure: c / (1 + L(c)), in linear
// light; non-finite or negative input gives black.
HDRF_HD Float3 ReinhardPixel(Float3 c) {
  // Not finite (NaN fails every comparison) gives black.
  if (!(fabsf(c.x) <= 3.4e38f && fabsf(c.y) <= 3.4e38f && fabsf(c.z) <= 3.4e38f)) return {0, 0, 0};
  c = {fmaxf(0.f, c.x), fmaxf(0.f, c.y), fmaxf(0.f, c.z)};
  const float l = Luminance(c);
  return l > 0 ? c * (1.f / (1.f + l)) : Float3{0, 0, 0};
}

namespace reinhard {
OperatorDecl Declaration();  // key "reinhard"
}  // namespace reinhard

}  // namespace hdrf::tonemap
