// Exposure and gamma: a scale (in stops, relative to the image's own log-average where the
// automatic key is on), clipping at display white, and a power (1 / gamma) on top.
#pragma once

#include "tonemap/operator.h"

namespace hdrf::tonemap::exposure {

// The scale that maps an image's log-average luminance to 0.18 (mid-grey) and then adds
// `stops`; without the automatic key, 2^stops alone.
float Scale(const Float3* rgb, std::size_t n, bool auto_key, double stops, double key = 0.18);

OperatorDecl Declaration();  // key "exposure"

}  // namespace hdrf::tonemap::exposure
