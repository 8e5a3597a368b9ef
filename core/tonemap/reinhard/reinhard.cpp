#include "tonemap/reinhard/reinhard.h"

#include "tonemap/pixel_operator.h"

namespace hdrf::tonemap {

namespace reinhard {
OperatorDecl Declaration() {
  OperatorDecl d;
  d.key = "reinhard";
  d.label = "Reinhard (global)";
  d.help = "The photographic operator: the image's log-average luminance maps to the key, then L / (1 + L).";
  d.params = {{"key", "Key", ParamDecl::Kind::kReal, 0.01, 1, 0.18, "", "Display value the log-average luminance maps to."},
              detail::ExposureParam(), detail::AutoKeyParam()};
  d.make = [](const Params& p, Device) {
    return detail::MakePixelOperator(p.at("auto_key") != 0, p.at("exposure"), p.at("key"), [](Float3 c) { return ReinhardPixel(c); });
  };
  return d;
}
}  // namespace reinhard

}  // namespace hdrf::tonemap
