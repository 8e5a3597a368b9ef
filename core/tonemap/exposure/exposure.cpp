#include "tonemap/exposure/exposure.h"

#include "tonemap/display.h"
#include "tonemap/pixel_operator.h"

namespace hdrf::tonemap {

namespace exposure {
float Scale(const Float3* rgb, std::size_t n, bool auto_key, double stops, double key) {
  const double base = auto_key ? key / LogAverageLuminance(rgb, n) : 1.0;
  return float(base * std::exp2(stops));
}
}  // namespace exposure

namespace exposure {
OperatorDecl Declaration() {
  OperatorDecl d;
  d.key = "exposure";
  d.label = "Exposure and gamma";
  d.help = "A scale in stops, clipped at white, with an extra gamma on top of the display's.";
  d.params = {detail::ExposureParam(),
              {"gamma", "Gamma", ParamDecl::Kind::kReal, 0.2, 5, 1, "", "Extra gamma: above 1 lifts the darks."},
              detail::AutoKeyParam()};
  d.make = [](const Params& p, Device) {
    const float inv = float(1 / p.at("gamma"));
    return detail::MakePixelOperator(p.at("auto_key") != 0, p.at("exposure"), 0.18, [inv](Float3 c) {
      auto g = [inv](float v) { return std::pow(std::clamp(v, 0.f, 1.f), inv); };
      return Float3{g(c.x), g(c.y), g(c.z)};
    });
  };
  return d;
}
}  // namespace exposure

}  // namespace hdrf::tonemap
