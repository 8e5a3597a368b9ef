#include "tonemap/linear/linear.h"

#include "tonemap/pixel_operator.h"

namespace hdrf::tonemap {

namespace linear {
OperatorDecl Declaration() {
  OperatorDecl d;
  d.key = "linear";
  d.label = "Linear";
  d.help = "Radiance scaled and clipped at white: what was measured, clipping included.";
  d.params = {detail::ExposureParam(), detail::AutoKeyParam()};
  d.make = [](const Params& p, Device) {
    return detail::MakePixelOperator(p.at("auto_key") != 0, p.at("exposure"), 0.18, [](Float3 c) { return c; });
  };
  return d;
}
}  // namespace linear

}  // namespace hdrf::tonemap
