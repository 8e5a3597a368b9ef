// What the three global per-pixel operators (Reinhard, exposure/gamma, linear) share: the
// automatic key and an Operator that applies a per-pixel function to the scaled radiance.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/image_view.h"
#include "common/parallel.h"
#include "tonemap/exposure/exposure.h"
#include "tonemap/operator.h"

namespace hdrf::tonemap::detail {

inline ParamDecl ExposureParam() {
  return {"exposure", "Exposure", ParamDecl::Kind::kReal, -12, 12, 0, "stops", "Brightness change, in stops."};
}
inline ParamDecl AutoKeyParam() {
  return {"auto_key", "Automatic key", ParamDecl::Kind::kBool, 0, 1, 1, "",
          "Scale each frame so that its log-average luminance is mid-grey (follows auto exposure)."};
}

// A per-pixel global operator: f(scaled colour) -> display-linear colour.
template <typename F>
class PixelOperator final : public Operator {
 public:
  PixelOperator(bool auto_key, double stops, double key, F f) : auto_key_(auto_key), stops_(stops), key_(key), f_(f) {}
  void Map(const RadianceImage& in, Image<Float3>& out, FrameTime) override {
    if (out.width() != in.width() || out.height() != in.height()) out = Image<Float3>(in.width(), in.height());
    scale_ = exposure::Scale(in.data(), in.size(), auto_key_, stops_, key_);
    has_scale_ = true;
    const float s = scale_;
    const F f = f_;
    ImageView<const Float3> src = View(in);
    ImageView<Float3> dst = View(out);
    par::ForEachPixel(par::Host{}, in.width(), in.height(), [=](int x, int y) { dst(x, y) = Apply(src(x, y), s, f); });
  }
  std::vector<Float3> MapList(const std::vector<Float3>& in) override {
    const float s = has_scale_ ? scale_ : exposure::Scale(in.data(), in.size(), auto_key_, stops_, key_);
    std::vector<Float3> out(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = Apply(in[i], s, f_);
    return out;
  }

 private:
  static Float3 Apply(Float3 c, float s, const F& f) {
    if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z))) return {0, 0, 0};
    const Float3 d = f(Float3{std::max(0.f, c.x), std::max(0.f, c.y), std::max(0.f, c.z)} * s);
    return {std::clamp(d.x, 0.f, 1.f), std::clamp(d.y, 0.f, 1.f), std::clamp(d.z, 0.f, 1.f)};
  }
  bool auto_key_;
  double stops_, key_;
  F f_;
  float scale_ = 1;
  bool has_scale_ = false;
};

template <typename F>
std::unique_ptr<Operator> MakePixelOperator(bool auto_key, double stops, double key, F f) {
  return std::make_unique<PixelOperator<F>>(auto_key, stops, key, f);
}


}  // namespace hdrf::tonemap::detail
