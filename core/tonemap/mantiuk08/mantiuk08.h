// Display-adaptive tone mapping (Mantiuk, Daly, Kerofsky, "Display Adaptive Tone Mapping",
// SIGGRAPH 2008): a global tone curve chosen, per image, to minimise the visible difference
// between the contrasts the scene shows and those the display can reproduce, under a model
// of the display (gamma, peak, black level, reflected ambient light) and of vision (contrast
// sensitivity, luminance and contrast masking). For video the curve is low-pass filtered in
// time at the actual frame rate.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "common/image.h"
#include "tonemap/mantiuk08/mantiuk08_impl.h"
#include "tonemap/operator.h"

namespace hdrf::tonemap::m08 {

// Gamma-gain-black-ambient display: L(v) = v^gamma (peak - black) + black + k / pi * ambient.
struct DisplayModel {
  double gamma = 2.2;         // display gamma
  double peak = 200;          // peak luminance, cd/m^2
  double black = 0.8;         // black level, cd/m^2
  double reflectivity = 0.01; // screen reflectivity
  double ambient = 60;        // ambient illuminance, lux
  double Offset() const;      // luminance at v = 0: black + reflected ambient
  double MinLuminance() const { return Offset(); }
  double MaxLuminance() const { return peak - black + Offset(); }
  void Check() const;  // throws SettingError for a display that cannot exist
};

struct Options {
  DisplayModel display;
  double ppd = 30;               // pixels per visual degree (sets the analysed bands)
  double viewing_distance = 0.5; // metres (in the contrast sensitivity model)
  double contrast = 1;           // contrast enhancement (1 = preserve the scene's contrast)
  double saturation = 1;         // colour saturation after tone mapping (1 = preserve)
  double scene_adaptation = 1000;// cd/m^2 the scene is seen at; 0 = each background's own
  bool contrast_masking = true, luminance_masking = true, csf = true;  // vision model parts
  bool temporal = true;          // low-pass the curve over time (video only)
  double temporal_cutoff = 0.5;  // Hz
  double hold_stops = 2;         // video: largest shift that holds the mean brightness steady (0 = off)
  double hold_cutoff = 0.1;      // Hz: the pace at which the held brightness follows the view
  void Check() const;
};

// Number of bands analysed for a given pixels-per-degree: down to the first band whose
// centre frequency is at most 3 cycles per degree.
int BandCount(double ppd);

// Counts of (band, background node, contrast bin) over the image, and their total (the
// zero-contrast bin left out).
struct Density {
  int bands = 0;
  std::vector<double> count;  // [band][node][bin]
  double total = 0;
  double& at(int b, int node, int bin) { return count[(std::size_t(b) * kNodes + std::size_t(node)) * kContrastBins + std::size_t(bin)]; }
  double at(int b, int node, int bin) const {
    return count[(std::size_t(b) * kNodes + std::size_t(node)) * kContrastBins + std::size_t(bin)];
  }
};

// log10 display luminance at each node.
using ToneCurve = std::array<double, kNodes>;

// Smallest positive luminance of the image (at least kMinLum): the floor of the logs.
float LuminanceFloor(const RadianceImage& rgb);
// The conditional density of the image (CPU; OpenMP).
Density ComputeDensity(const RadianceImage& rgb, float floor, int bands);
// The contrast histogram's per-band counts fixed up where a background has only flat field
// (a pair of threshold contrasts is added so that the curve stays defined there), and the
// total. Called by ComputeDensity (and by the CUDA path on its downloaded counts).
void FinishDensity(Density& d);

// The optimal curve for a density under `o` (the display, contrast, vision model). Throws
// Error when the image has no usable pixels. `iterations` receives how many re-linearised
// quadratic programs were solved.
ToneCurve OptimiseCurve(const Density& d, const Options& o, int* iterations = nullptr);

// The lookup tables ApplyCurve uses.
CurveLut MakeLut(const ToneCurve& y, const Options& o, float floor);

// Time filter of the curve: two cascaded one-pole low-passes per node, each with time
// constant 1 / (2 pi cutoff), advanced by the actual time between frames (so a slow or
// uneven frame rate filters as much per second as a steady one). The filtered curve is
// clamped to the display range.
class CurveFilter {
 public:
  // `t` < 0 (a still) resets the filter and returns `curve` unchanged.
  ToneCurve Update(const ToneCurve& curve, double t, double cutoff_hz, double y_min, double y_max);
  void Reset() { started_ = false; }

 private:
  bool started_ = false;
  double last_t_ = 0;
  ToneCurve stage1_{}, stage2_{};
};

// Pixels per node of their own log luminance (background node plus contrast bin of the
// finest band), the weights of a view's mean displayed level.
std::array<double, kNodes> PixelHistogram(const Density& d);

// Holds the view's mean displayed level steady while what is in view changes: the curve is
// shifted up or down (by at most `max_shift` log10 units, clamped to the display range) so
// that its mean over the frame's pixels follows a low-pass (two one-pole stages, cut-off
// `cutoff_hz`, slower than the curve filter's) of the mean the unshifted curve gives. The shape of the
// curve, and so the contrast within the frame, is the curve's own; a pan from bright to dark
// surfaces brightens the view gradually, as eyes adapt, instead of at once.
class BrightnessHold {
 public:
  // `t` < 0 (a still) resets the hold and returns `curve` unchanged.
  ToneCurve Update(const ToneCurve& curve, const std::array<double, kNodes>& pixels, double t, double cutoff_hz,
                   double max_shift, double y_min, double y_max);
  void Reset() { started_ = false; }
  double shift() const { return shift_; }  // of the last frame, log10 units

 private:
  bool started_ = false;
  double last_t_ = 0, stage1_ = 0, stage2_ = 0, shift_ = 0;
};

// The GPU path (CUDA builds; elsewhere every call throws saying the build has no CUDA
// backend): the image stays on the GPU between the density and the apply step; the curve is
// optimised on the host as for the CPU. The counts equal the CPU's (the same per-element
// steps, no fused multiply-adds) except where log10 rounds differently by one unit in the
// last place at a bin edge.
class CudaWorkspace {
 public:
  CudaWorkspace();
  ~CudaWorkspace();
  CudaWorkspace(const CudaWorkspace&) = delete;
  CudaWorkspace& operator=(const CudaWorkspace&) = delete;
  void Upload(const RadianceImage& rgb);
  Density ComputeDensity(float floor, int bands);
  void Apply(const CurveLut& lut, Image<Float3>& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The operator declaration (key "mantiuk08").
OperatorDecl Declaration();
Options OptionsFrom(const Params& p);

}  // namespace hdrf::tonemap::m08
