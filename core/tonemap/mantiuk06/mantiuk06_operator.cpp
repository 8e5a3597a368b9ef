// The Mantiuk 2006 operator behind the common Operator interface, with its declaration.
#include "tonemap/mantiuk06/mantiuk06.h"

#include "common/error.h"

namespace hdrf::tonemap::m06 {

namespace {
class Mantiuk06 final : public Operator {
 public:
  Mantiuk06(const Options& o, Device device) : o_(o), device_(device) {
    o_.Check();
    std::string why;
    if (device == Device::kCuda && !CudaAvailable(&why)) throw Error("mantiuk06 on CUDA: " + why);
    if (device == Device::kCuda) gpu_ = std::make_unique<CudaWorkspace>();
  }
  void Map(const RadianceImage& in, Image<Float3>& out, FrameTime) override {
    last_ = gpu_ ? gpu_->Map(in, out, o_) : m06::Map(in, out, o_);
    LearnCurve(in, out);
  }

 private:
  Options o_;
  Device device_;
  Result last_;
  std::unique_ptr<CudaWorkspace> gpu_;
};
}  // namespace

Options OptionsFrom(const Params& p) {
  Options o;
  o.equalise = p.at("equalise") != 0;
  o.contrast = p.at("contrast");
  o.saturation = p.at("saturation");
  o.detail = p.at("detail");
  o.iterations = int(p.at("iterations"));
  return o;
}

OperatorDecl Declaration() {
  using K = ParamDecl::Kind;
  OperatorDecl d;
  d.key = "mantiuk06";
  d.label = "Mantiuk 2006 (contrast domain)";
  d.help = "Local contrast at every scale compressed in a perceptual response space: details stay visible "
           "while large luminance differences shrink to fit the display.";
  d.params = {
      {"contrast", "Contrast factor", K::kReal, 0.01, 1, 0.1, "",
       "Mapping: scale of the contrast response (smaller compresses more). Equalisation: its strength."},
      {"equalise", "Contrast equalisation", K::kBool, 0, 1, 0, "",
       "Flatten the histogram of contrasts instead of scaling them (sharper, less natural)."},
      {"saturation", "Saturation", K::kReal, 0, 2, 0.8, "×", "Exponent of the colour ratios: below 1 desaturates."},
      {"detail", "Detail", K::kReal, 0.5, 10, 1, "×", "Above 1 treats contrasts as larger: stronger local detail."},
      {"iterations", "Solver iterations", K::kInt, 10, 1000, 200, "", "Most conjugate-gradient iterations per frame."},
  };
  d.local = true;
  d.make = [](const Params& p, Device dev) -> std::unique_ptr<Operator> {
    return std::make_unique<Mantiuk06>(OptionsFrom(p), dev);
  };
  return d;
}

}  // namespace hdrf::tonemap::m06
