// The Mantiuk 2008 operator behind the common Operator interface: its declared parameters
// and display presets, and the per-frame steps (density, curve, time filter, apply).
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/parallel.h"
#include "tonemap/mantiuk08/mantiuk08.h"

namespace hdrf::tonemap::m08 {

namespace {

bool NoData(Float3 c) {
  return !(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) || (c.x == 0 && c.y == 0 && c.z == 0);
}

class Mantiuk08 final : public Operator {
 public:
  Mantiuk08(const Options& o, Device device) : o_(o) {
    o_.Check();
    std::string why;
    if (device == Device::kCuda && !CudaAvailable(&why)) throw Error("mantiuk08 on CUDA: " + why);
    if (device == Device::kCuda) gpu_ = std::make_unique<CudaWorkspace>();
  }

  void Map(const RadianceImage& in, Image<Float3>& out, FrameTime t) override {
    if (out.width() != in.width() || out.height() != in.height()) out = Image<Float3>(in.width(), in.height());
    const float floor = LuminanceFloor(in);
    Density d;
    if (gpu_) {
      gpu_->Upload(in);
      d = gpu_->ComputeDensity(floor, BandCount(o_.ppd));
    } else {
      d = ComputeDensity(in, floor, BandCount(o_.ppd));
    }
    bool flat = d.total == 0;
    ToneCurve y{};
    if (!flat) {
      y = OptimiseCurve(d, o_);
    } else {
      // Nothing to map (empty or a single level): mid-grey display level for everything.
      y.fill(std::log10(o_.display.Offset() + 0.18 * (o_.display.peak - o_.display.black)));
    }
    const double y_min = std::log10(o_.display.MinLuminance()), y_max = std::log10(o_.display.MaxLuminance());
    ToneCurve unheld = y;
    if (o_.temporal) {
      y = unheld = filter_.Update(y, t.seconds, o_.temporal_cutoff, y_min, y_max);
      if (!flat) y = hold_.Update(y, PixelHistogram(d), t.seconds, o_.hold_cutoff, o_.hold_stops * std::log10(2.0), y_min, y_max);
    }
    lut_ = MakeLut(y, o_, floor);
    // Lists (the mesh in the 3-D view) take the curve without the hold: the hold steadies a
    // view whose content the camera changes; the whole model's content does not change.
    list_lut_ = hold_.shift() != 0 ? MakeLut(unheld, o_, floor) : lut_;
    has_lut_ = true;
    curve_ = y;
    if (gpu_) {
      gpu_->Apply(lut_, out);
      return;
    }
    const CurveLut lut = lut_;
    ImageView<const Float3> src = View(in);
    ImageView<Float3> dst = View(out);
    par::ForEachPixel(par::Host{}, in.width(), in.height(), [=](int x, int yy) {
      const Float3 c = src(x, yy);
      dst(x, yy) = NoData(c) ? Float3{0, 0, 0} : ApplyCurve(c, lut);
    });
  }

  std::vector<Float3> MapList(const std::vector<Float3>& in) override {
    if (!has_lut_) return Operator::MapList(in);
    std::vector<Float3> out(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = NoData(in[i]) ? Float3{0, 0, 0} : ApplyCurve(in[i], list_lut_);
    return out;
  }

  Curve LastCurve() const override {
    Curve c;
    if (!has_lut_) return c;
    for (int i = 0; i < kNodes; ++i) {
      c.log_lum.push_back(kLogMin + kStep * i);
      c.display.push_back(std::clamp((std::pow(10.0, curve_[std::size_t(i)]) - o_.display.Offset()) /
                                         (o_.display.peak - o_.display.black), 0.0, 1.0));
    }
    return c;
  }

 private:
  Options o_;
  CurveFilter filter_;
  BrightnessHold hold_;
  CurveLut lut_{}, list_lut_{};
  ToneCurve curve_{};
  bool has_lut_ = false;
  std::unique_ptr<CudaWorkspace> gpu_;
};

}  // namespace

Options OptionsFrom(const Params& p) {
  Options o;
  o.display.gamma = p.at("gamma");
  o.display.peak = p.at("peak");
  o.display.black = p.at("black");
  o.display.reflectivity = p.at("reflectivity");
  o.display.ambient = p.at("ambient");
  o.ppd = p.at("ppd");
  o.viewing_distance = p.at("distance");
  o.contrast = p.at("contrast");
  o.saturation = p.at("saturation");
  o.scene_adaptation = p.at("scene_adaptation");
  o.contrast_masking = p.at("contrast_masking") != 0;
  o.luminance_masking = p.at("luminance_masking") != 0;
  o.csf = p.at("csf") != 0;
  o.temporal = p.at("temporal") != 0;
  o.temporal_cutoff = p.at("temporal_hz");
  o.hold_stops = p.at("hold");
  o.hold_cutoff = p.at("hold_hz");
  return o;
}

OperatorDecl Declaration() {
  using K = ParamDecl::Kind;
  OperatorDecl d;
  d.key = "mantiuk08";
  d.label = "Mantiuk 2008 (display adaptive)";
  d.help = "A global tone curve fitted per frame so that the display shows the scene's visible contrasts as "
           "closely as it can, for the display and viewing conditions below.";
  d.params = {
      {"gamma", "Display gamma", K::kReal, 1, 4, 2.2, "", "Gamma of the display's response."},
      {"peak", "Peak luminance", K::kReal, 10, 10000, 200, "cd/m²", "Luminance of display white."},
      {"black", "Black level", K::kReal, 0.001, 50, 0.8, "cd/m²", "Luminance of display black in a dark room."},
      {"reflectivity", "Screen reflectivity", K::kReal, 0, 0.2, 0.01, "", "Fraction of ambient light the screen reflects."},
      {"ambient", "Ambient light", K::kReal, 0, 100000, 60, "lux", "Illuminance falling on the screen."},
      {"ppd", "Pixels per degree", K::kReal, 1, 200, 30, "px/°", "Display resolution at the viewing distance; sets the analysed bands."},
      {"distance", "Viewing distance", K::kReal, 0.1, 10, 0.5, "m", "Distance from the eye to the screen."},
      {"contrast", "Contrast enhancement", K::kReal, 0.25, 4, 1, "×", "1 preserves the scene's contrast; above 1 enhances it."},
      {"saturation", "Saturation", K::kReal, 0, 2, 1, "×", "1 preserves colour appearance; below 1 desaturates."},
      {"scene_adaptation", "Scene adaptation", K::kReal, 0, 1e6, 1000, "cd/m²",
       "Luminance the original scene is seen at; 0 takes each region's own luminance."},
      {"contrast_masking", "Contrast masking", K::kBool, 0, 1, 1, "", "Model the lower visibility of contrast on contrast."},
      {"luminance_masking", "Luminance masking", K::kBool, 0, 1, 1, "", "Model the lower sensitivity at low luminance."},
      {"csf", "Contrast sensitivity", K::kBool, 0, 1, 1, "", "Weigh contrasts by the eye's sensitivity to their frequency."},
      {"temporal", "Temporal filter", K::kBool, 0, 1, 1, "", "For video: low-pass the curve over time so the view does not flicker."},
      {"temporal_hz", "Filter cut-off", K::kReal, 0.05, 10, 0.5, "Hz", "Cut-off frequency of the curve's time filter."},
      {"hold", "Brightness hold", K::kReal, 0, 4, 2, "stops",
       "For video: up to this many stops, the time filter holds the view's mean brightness steady while the camera "
       "turns to brighter or darker surfaces, and lets it adapt at the pace below. 0 turns it off."},
      {"hold_hz", "Brightness adaptation", K::kReal, 0.01, 10, 0.1, "Hz",
       "Cut-off frequency of the held brightness: at 0.1 Hz the view adapts to what is in view over about three seconds."},
  };
  d.presets = {
      {"lcd_office", "LCD, office", {{"gamma", 2.2}, {"peak", 100}, {"black", 0.8}, {"ambient", 400}, {"reflectivity", 0.01}}},
      {"lcd", "LCD", {{"gamma", 2.2}, {"peak", 200}, {"black", 0.8}, {"ambient", 60}, {"reflectivity", 0.01}}},
      {"lcd_bright", "LCD, bright", {{"gamma", 2.6}, {"peak", 500}, {"black", 0.5}, {"ambient", 10}, {"reflectivity", 0.01}}},
      {"crt", "CRT", {{"gamma", 2.2}, {"peak", 80}, {"black", 1}, {"ambient", 60}, {"reflectivity", 0.02}}},
  };
  d.local = false;
  d.make = [](const Params& p, Device dev) -> std::unique_ptr<Operator> {
    return std::make_unique<Mantiuk08>(OptionsFrom(p), dev);
  };
  return d;
}

}  // namespace hdrf::tonemap::m08
