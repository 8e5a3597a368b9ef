// Contrast-domain tone mapping (Mantiuk, Myszkowski, Seidel, "A Perceptual Framework for
// Contrast Processing of High Dynamic Range Images", ACM TAP 2006): local contrasts at all
// scales are compressed in a perceptually uniform response space, so that small details
// keep their visibility while the large luminance differences shrink to fit the display.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "common/image.h"
#include "tonemap/mantiuk06/mantiuk06_impl.h"
#include "tonemap/operator.h"

namespace hdrf::tonemap::m06 {

struct Options {
  bool equalise = false;   // contrast equalisation instead of contrast mapping
  double contrast = 0.1;   // mapping: response scale factor; equalisation: strength
  double saturation = 0.8; // colour saturation (exponent of the colour ratios)
  double detail = 1;       // detail factor: >1 treats contrasts as larger (stronger local detail)
  int iterations = 200;    // most conjugate-gradient iterations
  double tolerance = 1e-3; // relative residual to stop at
  void Check() const;
};

// The transducer tables (response in just-noticeable differences against log10 contrast),
// built from the contrast discrimination threshold model (see mantiuk06_impl.h).
const Transducer& DefaultTransducer();

struct Result {
  int iterations = 0;
  double residual = 0;  // relative residual reached
  bool converged = false;
};

// Radiance to display-linear RGB on the CPU. Pixels with no data are black. Returns the
// solver's outcome (a fit that stops at the iteration limit is still usable: reported, not
// fatal, as for the reference implementation).
Result Map(const RadianceImage& in, Image<Float3>& out, const Options& o);

// The same on the GPU (CUDA builds; elsewhere throws saying the build has no CUDA backend):
// the pyramid, the transducer and the conjugate-gradient solve on the device, with the
// same per-element steps; the two quantiles and the equalisation's histogram on the host.
Result MapCuda(const RadianceImage& in, Image<Float3>& out, const Options& o);
// The same, keeping the device buffers between frames (for video).
class CudaWorkspace {
 public:
  CudaWorkspace();
  ~CudaWorkspace();
  CudaWorkspace(const CudaWorkspace&) = delete;
  CudaWorkspace& operator=(const CudaWorkspace&) = delete;
  Result Map(const RadianceImage& in, Image<Float3>& out, const Options& o);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Shared by both paths: the value at quantile q of the valid entries (a fine histogram,
// linear within a bin), and the equalisation's cumulative distribution of response
// magnitudes (kEqualiseBins + 1 entries, as fractions, over [0, top]).
float Quantile(const std::vector<float>& v, const std::vector<std::uint8_t>& valid, double q);
// Two quantiles from one histogram.
void Quantiles(const std::vector<float>& v, const std::vector<std::uint8_t>& valid, double q_lo, double q_hi, float* lo,
               float* hi);
constexpr int kEqualiseBins = 4096;
std::vector<float> EqualisationCdf(const std::vector<const std::vector<float>*>& gx,
                                   const std::vector<const std::vector<float>*>& gy, float* top);

OperatorDecl Declaration();  // key "mantiuk06"
Options OptionsFrom(const Params& p);

}  // namespace hdrf::tonemap::m06
