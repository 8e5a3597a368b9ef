// Radiometric calibration from an exposure sweep (docs/formats.md): camera response (Debevec &
// Malik; Robertson et al.; EMoR basis of Grossberg & Nayar), noise level function, HDR merge.
//
// Scale convention: a response is only defined up to one factor per channel. Every fit here
// returns f^-1 scaled so that f^-1(128) = 1 in each channel (level 128 = one unit of R).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/image.h"
#include "radiometry/pcf.h"
#include "radiometry/response.h"

namespace hdrf::radiometry {

// A static scene seen at several exposures; several frames may share one exposure.
struct Sweep {
  std::vector<ColorImage> images;
  std::vector<double> exposure_ms;  // one per image
  std::string source = "sweep";     // named in error messages (the folder)
};

// Refuses sweeps that cannot be calibrated, with the reason: fewer than two distinct
// exposures, images of different sizes, no pixel unclipped in two exposures, or a camera
// or scene that moved between exposures. Throws hdrf::Error naming sweep.source.
void CheckSweep(const Sweep& sweep);

// Levels treated as clipped (no information): below `lo` or above `hi`.
struct ClipLevels {
  int lo = 3, hi = 254;
};

// How many pairs of image regions swap brightness order between two frames of one static
// scene (taken at the same or at different exposures: the response is monotonic, so the
// order holds unless the camera or the scene moved). Pairs count where both regions are
// unclipped and 8 levels apart in both frames.
struct OrderChange {
  double share = 0;     // of the pairs considered
  long considered = 0;
  // Over all 201 DoRF curves with no motion at most 0.7 % swap; a 9-pixel shift swaps 18 %.
  bool moved() const { return considered > 200 && share > 0.05; }
};
OrderChange CompareBrightnessOrder(const ColorImage& first, const ColorImage& second, ClipLevels clip = {});

struct DebevecOptions {
  int samples = 6000;     // pixel locations sampled (stratified by brightness)
  double lambda = 100.0;  // smoothness weight on g'' (g = ln f^-1)
  // Passes of the noise-aware refinement on the level thresholds after the method's own
  // fit (each level set midway between the radiances where the sensor switches to the
  // levels below and above it, fitted by probit regression; see FitNoise). 0 gives the
  // classic method. It removes the pull of each level's average towards dense parts of the
  // scene's radiance histogram: on the 201 DoRF curves Robertson's worst error went from
  // 1.10 % to 0.84 % of the range (desk scene 1.52 % to 0.32 %), Debevec's from 0.73 % to
  // 0.57 % (desk 0.92 % to 0.19 %).
  int threshold_passes = 2;
  ClipLevels clip;
};
struct RobertsonOptions {
  int samples = 20000;  // pixel locations used
  int iterations = 60;
  // Weight of a second-difference penalty in the M-step, relative to the mean number of
  // observations per level. Exposures a constant ratio apart (half-stop brackets) leave the
  // curve undetermined up to a wave periodic in log radiance (Grossberg & Nayar); with no
  // penalty it shows as +-1 % ripples on strongly compressive curves.
  double smoothness = 10.0;
  // Passes of the noise-aware refinement on the level thresholds after the method's own
  // fit (each level set midway between the radiances where the sensor switches to the
  // levels below and above it, fitted by probit regression; see FitNoise). 0 gives the
  // classic method. It removes the pull of each level's average towards dense parts of the
  // scene's radiance histogram: on the 201 DoRF curves Robertson's worst error went from
  // 1.10 % to 0.84 % of the range (desk scene 1.52 % to 0.32 %), Debevec's from 0.73 % to
  // 0.57 % (desk 0.92 % to 0.19 %).
  int threshold_passes = 2;
  ClipLevels clip;
};
struct EmorOptions {
  int components = 25;  // hinv_1..hinv_K of the basis (invemor.txt has 25)
  int threshold_passes = 2;  // of the Debevec curve it projects (DebevecOptions)
  ClipLevels clip;
};

// The EMoR inverse basis (invemor.txt of the CAVE distribution): g(B) = g0(B) + sum c_n h_n(B)
// sampled at B = j / 1023.
struct EmorBasis {
  std::vector<double> g0;
  std::vector<std::vector<double>> h;  // up to 25 components
  static EmorBasis Load(const std::filesystem::path& invemor_txt);  // throws InputError
};

struct ResponseFit {
  InverseResponse inverse;
  // Root-mean-square of ln(f^-1(I) / exposure) - ln(E) over the samples used (in natural
  // log units: 0.01 is about 1 %), per channel.
  std::array<double, 3> rms_log_residual{};
  std::array<int, 3> samples_used{};
  std::string method;
  // EMoR only: the largest difference over levels 5..250 between this curve and the
  // free-form Debevec curve of the same sweep (after one scale per channel), as a share of
  // the range, and the level where it is. Large (over 1 %) when the camera's response lies
  // outside what the basis can represent; then the free-form methods are the better choice.
  std::array<double, 3> basis_gap{};
  std::array<int, 3> basis_gap_level{};
};

ResponseFit FitDebevec(const Sweep& sweep, const DebevecOptions& options = {});
ResponseFit FitRobertson(const Sweep& sweep, const RobertsonOptions& options = {});
ResponseFit FitEmor(const Sweep& sweep, const EmorBasis& basis, const EmorOptions& options = {});

// The documented scale: divides each channel by its value at level 128 (left alone where 0).
void ScaleToUnitAt128(InverseResponse& inverse);

// The factor s that brings channel c of `estimate` closest to `reference` over levels lo..hi
// (least squares on s f^-1_est - f^-1_ref); 1 when the estimate is all zero there.
double ScaleOnto(const InverseResponse& estimate, const InverseResponse& reference, int c, int lo,
                 int hi);

// Makes each channel non-decreasing by least-squares isotonic regression (pool adjacent
// violators), then rescales so that f^-1(128) = 1.
void EnforceMonotonic(InverseResponse& inverse);

// Noise level function, Var R = R sigma_s^2 + sigma_c^2, measured where the sensor itself
// draws the line between two levels. Each pixel's radiance L comes from the other exposures
// of the sweep (an inverse-variance weighted merge of the exposures whose predicted level is
// 24..236, leaving its own exposure out so that a sample's noise does not move its own
// R = L t). For every threshold k between
// levels k-1 and k, the share of samples below k as a function of R is a probit curve,
// Phi((tau_k - R) / sigma(tau_k)): a maximum-likelihood fit gives the threshold's radiance
// tau_k and the noise there, with no slope of f^-1 involved (the slope of a fitted response
// is least certain exactly where the constant noise term shows, in the dark levels) and no
// correction for quantisation needed. The spread that the merge's own error adds to R is
// subtracted, then sigma_k^2 = tau_k sigma_s^2 + sigma_c^2 is fitted, weighted by each
// threshold's precision. Clipped samples count as below or above (never truncated), so
// clipping needs no special case. Needs >= 3 frames for some exposure.
struct NoiseLevel {
  double level;     // the threshold k - 0.5, between levels k - 1 and k
  double radiance;  // tau: the R at which the sensor is equally likely to give either level
  double variance;  // sigma^2 of R there (the merge's own error removed)
  int count;        // samples within one sigma of tau
};
struct NoiseFit {
  NoiseModel noise;
  std::array<std::vector<NoiseLevel>, 3> levels;  // per channel, ascending thresholds
  std::array<double, 3> rms_relative_residual{};  // of the fit against the thresholds
};
NoiseFit FitNoise(const Sweep& sweep, const InverseResponse& inverse, ClipLevels clip = {});

// Weighted merge of a sweep into radiance L = f^-1(I) / exposure_ms, per channel. Each
// sample's confidence is the inverse of its variance under the calibrated noise model,
// Var(L) = (R sigma_s^2 + sigma_c^2 + q^2 / 12) / t^2 with q the local quantisation step of
// f^-1: near saturation q explodes and the sample fades out, as the PCF does. Clipped samples
// get no weight; pixels clipped in every exposure take the value of the exposure nearest to
// unclipped.
RadianceImage MergeHdr(const Sweep& sweep, const InverseResponse& inverse, const NoiseModel& noise,
                       ClipLevels clip = {});

// Consistency of a calibration: for each distinct exposure, the median over well-exposed
// samples (levels 32..224, where noise and quantisation are small) of
// |log2(f^-1(I)/exposure / L_merged)|, in stops.
struct ExposureConsistency {
  double exposure_ms;
  double median_abs_stops;
  long samples;
};
// With `noise`, only samples whose predicted noise (sqrt(R sigma_s^2 + sigma_c^2) / R) is
// under 5 % count: on a noisy camera the dark levels' spread is noise, not a wrong exposure.
std::vector<ExposureConsistency> MergeConsistency(const Sweep& sweep,
                                                  const InverseResponse& inverse,
                                                  const RadianceImage& merged,
                                                  ClipLevels clip = {},
                                                  const NoiseModel* noise = nullptr);

}  // namespace hdrf::radiometry
