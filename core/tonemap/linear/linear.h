// Linear: radiance scaled (exposure in stops, after the automatic key) and clipped at
// display white; no curve at all. The view that shows what was measured, clipping included.
#pragma once

#include "tonemap/operator.h"

namespace hdrf::tonemap::linear {

OperatorDecl Declaration();  // key "linear"

}  // namespace hdrf::tonemap::linear
