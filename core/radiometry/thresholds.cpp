// The level thresholds of a sweep: for each pair of levels, the radiance where the sensor
// switches and the noise there (a probit fit against the merged radiance). They give the
// noise level function (FitNoise) and the noise-aware refinement of a fitted response.
#include "radiometry/calibration.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <optional>
#include <sstream>

#include "common/error.h"
#include "radiometry/calibration_detail.h"

namespace hdrf::radiometry {

using namespace detail;

namespace detail {
namespace {

// Samples of one channel binned by their radiance R = L t (L from the other exposures), with
// the count of levels below each threshold and the variance the merge's error adds to R.
struct ThresholdData {
  static constexpr int kBins = 4096;                 // log-spaced over 5.5 decades
  std::vector<double> n, sum_r, sum_err;             // per bin
  std::vector<std::array<int, kLevels + 1>> below;   // per bin: samples with level < k
  explicit ThresholdData() : n(kBins, 0), sum_r(kBins, 0), sum_err(kBins, 0), below(kBins) {
    for (auto& b : below) b.fill(0);
  }
};

ThresholdData BinByMergedRadiance(const Sweep& s, const Groups& g, const std::array<float, kLevels>& t,
                                  int c, float sigma_s, float sigma_c, ClipLevels clip) {
  // Per level: noise variance of R under the current model and the quantisation step q;
  // a merge weight w = t^2 / (noise + q^2 / 12). Quantisation errors are taken as shared by
  // the frames of one exposure (a pixel that lands in a wide band lands there every time).
  std::array<double, kLevels> noise{}, quant{}, step{};
  for (int z = 0; z < kLevels; ++z) {
    const int zl = std::max(0, z - 1), zh = std::min(kLevels - 1, z + 1);
    step[std::size_t(z)] = (t[std::size_t(zh)] - t[std::size_t(zl)]) / double(zh - zl);
    quant[std::size_t(z)] = step[std::size_t(z)] * step[std::size_t(z)] / 12.0;
    noise[std::size_t(z)] = t[std::size_t(z)] * sigma_s * sigma_s + double(sigma_c) * sigma_c;
  }
  // Which exposures of a pixel enter its merge. Choosing frames by their own level truncates
  // their noise: near a cut only the frames pushed across it are kept, a dark pixel's L comes
  // out high and every threshold it sees is placed too high (sigma_c 10 % off with a loud
  // sensor). So a first merge over the well-exposed levels 40..224 predicts each exposure's
  // level, and an exposure enters the final merge, all its unclipped frames, when its
  // predicted level is within 24..236, whatever its frames show.
  constexpr int kFirstLo = 40, kFirstHi = 224, kUseLo = 24, kUseHi = 236;
  const double r_lo = t[kUseLo], r_hi = t[kUseHi];
  struct Sums {
    double a = 0, b = 0, noise = 0, quant = 0;  // sum w x, sum w, sum w^2 var, (sum w q)^2 / 12
  };
  const std::size_t npx = s.images[0].size();
  // Frames of exposure e at pixel p: those with levels in lo..hi, or (lo < 0) all unclipped
  // ones when the predicted R = l0 t_e is inside r_lo..r_hi.
  auto group_sums = [&](std::size_t e, std::size_t p, double l0) {
    Sums out;
    const double te = g.exposure[e];
    const bool by_level = l0 < 0;
    if (!by_level && (l0 * te < r_lo || l0 * te > r_hi)) return out;
    double wq = 0;
    for (int i : g.images[e]) {
      const int z = Level(s.images[std::size_t(i)][p], c);
      if (by_level ? (z < kFirstLo || z > kFirstHi) : Clipped(z, clip)) continue;
      const double w = te * te / (noise[std::size_t(z)] + quant[std::size_t(z)]);
      out.a += w * t[std::size_t(z)] / te;
      out.b += w;
      out.noise += w * w * noise[std::size_t(z)] / (te * te);
      wq += w * step[std::size_t(z)] / te;
    }
    out.quant = wq * wq / 12.0;
    return out;
  };
  std::vector<double> l0(npx, 0);
  for (std::size_t p = 0; p < npx; ++p) {
    double a = 0, b = 0;
    for (std::size_t e = 0; e < g.exposure.size(); ++e) {
      const Sums x = group_sums(e, p, -1);
      a += x.a, b += x.b;
    }
    l0[p] = b > 0 ? a / b : 0;
  }
  std::vector<Sums> total(npx);
  for (std::size_t e = 0; e < g.exposure.size(); ++e)
    for (std::size_t p = 0; p < npx; ++p) {
      if (!(l0[p] > 0)) continue;
      const Sums x = group_sums(e, p, l0[p]);
      total[p].a += x.a, total[p].b += x.b, total[p].noise += x.noise, total[p].quant += x.quant;
    }
  ThresholdData d;
  const double log_ref = std::log10(std::max(1e-30, double(t[128])));
  for (std::size_t e = 0; e < g.exposure.size(); ++e) {
    const double te = g.exposure[e];
    for (std::size_t p = 0; p < npx; ++p) {
      if (!(l0[p] > 0)) continue;
      const Sums own = group_sums(e, p, l0[p]);
      const double b = total[p].b - own.b;
      if (!(b > 1e-9 * total[p].b) || !(b > 0)) continue;  // seen in no other exposure
      const double R = (total[p].a - own.a) / b * te;
      if (!(R > 0)) continue;
      const double err = (total[p].noise - own.noise + total[p].quant - own.quant) / (b * b) * te * te;
      const int bin = int((std::log10(R) - log_ref + 4.0) / 5.5 * ThresholdData::kBins);
      if (bin < 0 || bin >= ThresholdData::kBins) continue;
      const auto k = std::size_t(bin);
      for (int i : g.images[e]) {
        d.n[k] += 1;
        d.sum_r[k] += R;
        d.sum_err[k] += err;
        d.below[k][Level(s.images[std::size_t(i)][p], c) + 1u] += 1;
      }
    }
  }
  for (auto& b : d.below)
    for (int z = 1; z <= kLevels; ++z) b[std::size_t(z)] += b[std::size_t(z - 1)];
  return d;
}

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double NormalPdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * 3.14159265358979323846); }

struct Threshold {
  double tau, variance, variance_of_variance, count;
};

// Maximum-likelihood probit fit of P(level < k | R) = Phi(a - b R), i.e. tau = a / b and
// sigma = 1 / b, by Newton steps (the log-likelihood is concave in a, b). Empty where the
// data do not pin the threshold down.
std::optional<Threshold> FitThreshold(const ThresholdData& d, int k) {
  // Start from where the share below k crosses 84 %, 50 % and 16 % (runs of 8 bins).
  double r84 = -1, r50 = -1, r16 = -1;
  for (int b = 0; b + 8 <= ThresholdData::kBins && r16 < 0; ++b) {
    double nb = 0, nn = 0, rr = 0;
    for (int j = b; j < b + 8; ++j) {
      nb += d.below[std::size_t(j)][std::size_t(k)];
      nn += d.n[std::size_t(j)];
      rr += d.sum_r[std::size_t(j)];
    }
    if (nn < 20) continue;
    const double share = nb / nn, R = rr / nn;
    if (r84 < 0 && share < 0.84) r84 = R;
    if (r50 < 0 && share < 0.5) r50 = R;
    if (r16 < 0 && share < 0.16) r16 = R;
  }
  if (r84 < 0 || r50 < 0 || r16 < 0) return std::nullopt;
  const double sigma0 = std::max(1e-9 * r50, 0.5 * (r16 - r84));
  double a = r50 / sigma0, b = 1 / sigma0;
  double h00 = 0, h01 = 0, h11 = 0;
  bool converged = false;
  for (int it = 0; it < 40 && !converged; ++it) {
    const double tau = a / b, sigma = 1 / b;
    double g0 = 0, g1 = 0;
    h00 = h01 = h11 = 0;
    for (int bin = 0; bin < ThresholdData::kBins; ++bin) {
      const double n = d.n[std::size_t(bin)];
      if (n == 0) continue;
      const double R = d.sum_r[std::size_t(bin)] / n;
      if (std::abs(R - tau) > 6 * sigma) continue;
      const double y = d.below[std::size_t(bin)][std::size_t(k)];
      const double eta = a - b * R;
      const double P = std::clamp(NormalCdf(eta), 1e-12, 1 - 1e-12), f = NormalPdf(eta);
      const double score = y * f / P - (n - y) * f / (1 - P);
      const double info = n * f * f / (P * (1 - P));  // Fisher information in eta
      g0 += score, g1 -= R * score;
      h00 += info, h01 -= R * info, h11 += R * R * info;
    }
    const double det = h00 * h11 - h01 * h01;
    if (!(det > 0)) return std::nullopt;
    const double da = (h11 * g0 - h01 * g1) / det, db = (h00 * g1 - h01 * g0) / det;
    a += da, b += db;
    if (!(b > 0)) return std::nullopt;
    converged = std::abs(db) < 1e-7 * b && std::abs(da) < 1e-7 * (std::abs(a) + 1);
  }
  if (!converged) return std::nullopt;
  const double det = h00 * h11 - h01 * h01;
  const double var_b = h00 / det;
  const double tau = a / b, sigma = 1 / b;
  // Samples within one sigma: their count, and the variance the merge's error adds to R.
  double count = 0, err = 0;
  for (int bin = 0; bin < ThresholdData::kBins; ++bin) {
    const double n = d.n[std::size_t(bin)];
    if (n > 0 && std::abs(d.sum_r[std::size_t(bin)] / n - tau) < sigma)
      count += n, err += d.sum_err[std::size_t(bin)];
  }
  if (count < 50) return std::nullopt;
  const double variance = sigma * sigma - err / count;
  if (!(variance > 0)) return std::nullopt;
  return Threshold{tau, variance, std::pow(2 / (b * b * b), 2) * var_b, count};
}

// Weighted least squares of variance = slope R + offset; offset 0 where the data put it
// below zero. Returns {slope, offset}.
std::pair<double, double> FitVarianceLine(const std::vector<Threshold>& th, const std::vector<bool>& use) {
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < th.size(); ++i) {
    if (!use[i]) continue;
    const double w = 1 / th[i].variance_of_variance, x = th[i].tau, y = th[i].variance;
    sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
  }
  double slope = (sw * sxy - sx * sy) / (sw * sxx - sx * sx);
  double offset = (sy - slope * sx) / sw;
  if (!(offset >= 0)) offset = 0, slope = sxy / sxx;
  return {std::max(0.0, slope), offset};
}


// Every threshold of channel c that the data pin down, with its level k (between levels
// k - 1 and k), from a merge weighted by the noise model (sigma_s, sigma_c).
struct ChannelThresholds {
  std::vector<int> level;
  std::vector<Threshold> fit;
};
ChannelThresholds FitChannelThresholds(const Sweep& s, const Groups& g, const std::array<float, kLevels>& t,
                                       int c, float sigma_s, float sigma_c, ClipLevels clip) {
  const ThresholdData d = BinByMergedRadiance(s, g, t, c, sigma_s, sigma_c, clip);
  ChannelThresholds out;
  for (int k = clip.lo + 1; k <= clip.hi; ++k)
    if (const auto x = FitThreshold(d, k)) out.level.push_back(k), out.fit.push_back(*x);
  return out;
}

// The noise model the first merge is weighted with, before any is fitted: generic, in the
// units of the curve (f^-1(128) is one unit of R).
std::pair<float, float> GenericNoise(const std::array<float, kLevels>& t) {
  const float ref = std::max(1e-12f, t[128]);
  return {0.02f * std::sqrt(ref), 0.01f * ref};
}

}  // namespace

// The noise-aware last step of Debevec and Robertson. Both set f^-1(z) to an average of the
// radiance of the samples seen at level z, which is E[R | z]: where the noise spans several
// levels it leans towards wherever the scene's radiance histogram is dense (a flat wall at
// one radiance, repeated at every exposure), by up to a noise sigma. Regressing the level on
// the radiance instead (the probit fit of each threshold above) has no such bias: each level
// takes the midpoint of its two fitted thresholds; levels whose thresholds did not fit keep
// their value. Each pass re-merges L with the refined curve and a noise model fitted to the
// previous pass's thresholds.
void RefineOnThresholds(const Sweep& s, const Groups& g, InverseResponse& inv, int passes, ClipLevels clip) {
  if (passes <= 0) return;
  EnforceMonotonic(inv);  // the merge needs a monotonic curve with f^-1(128) = 1
  std::array<std::pair<float, float>, 3> noise;
  for (int c = 0; c < 3; ++c) noise[std::size_t(c)] = GenericNoise(inv.table[std::size_t(c)]);
  for (int pass = 0; pass < passes; ++pass) {
    for (int c = 0; c < 3; ++c) {
      auto& t = inv.table[std::size_t(c)];
      auto& [sigma_s, sigma_c] = noise[std::size_t(c)];
      const ChannelThresholds th = FitChannelThresholds(s, g, t, c, sigma_s, sigma_c, clip);
      std::array<double, kLevels + 1> tau;
      tau.fill(NAN);
      for (std::size_t i = 0; i < th.level.size(); ++i) tau[std::size_t(th.level[i])] = th.fit[i].tau;
      for (int z = clip.lo + 1; z < clip.hi; ++z)
        if (std::isfinite(tau[std::size_t(z)]) && std::isfinite(tau[std::size_t(z + 1)]))
          t[std::size_t(z)] = float(0.5 * (tau[std::size_t(z)] + tau[std::size_t(z + 1)]));
      if (th.fit.size() >= 3) {
        const auto [slope, offset] = FitVarianceLine(th.fit, std::vector<bool>(th.fit.size(), true));
        if (slope > 0 || offset > 0) sigma_s = float(std::sqrt(slope)), sigma_c = float(std::sqrt(offset));
      }
    }
    EnforceMonotonic(inv);
  }
}

}  // namespace detail

NoiseFit FitNoise(const Sweep& s, const InverseResponse& inv, ClipLevels clip) {
  const Groups g = GroupByExposure(s);
  bool repeats = false;
  for (const auto& grp : g.images) repeats |= grp.size() >= 3;
  if (!repeats)
    throw Error(s.source + ": the noise level function needs at least 3 frames per exposure "
                           "(repeated frames); this sweep has one or two");
  if (g.exposure.size() < 2)
    throw Error(s.source + ": the noise level function needs at least two distinct exposures");
  NoiseFit out;
  for (int c = 0; c < 3; ++c) {
    const auto& t = inv.table[std::size_t(c)];
    // The merge weights need a noise model: a generic one first, then the fitted one.
    auto [sigma_s, sigma_c] = GenericNoise(t);
    ChannelThresholds fitted;
    std::vector<bool> use;
    double slope = 0, offset = 0;
    for (int pass = 0; pass < 2; ++pass) {
      fitted = FitChannelThresholds(s, g, t, c, sigma_s, sigma_c, clip);
      const std::vector<Threshold>& th = fitted.fit;
      if (th.size() < 3)
        throw Error(s.source + ": too few level thresholds crossed by unclipped, repeated pixels to "
                               "fit the noise of channel " + std::to_string(c) + " (" +
                    std::to_string(th.size()) + ")");
      // Fit, then once more without thresholds more than 4 standard errors off the line.
      use.assign(th.size(), true);
      std::tie(slope, offset) = FitVarianceLine(th, use);
      for (std::size_t i = 0; i < th.size(); ++i)
        use[i] = std::abs(th[i].variance - (slope * th[i].tau + offset)) <
                 4 * std::sqrt(th[i].variance_of_variance);
      if (std::count(use.begin(), use.end(), true) >= 3) std::tie(slope, offset) = FitVarianceLine(th, use);
      sigma_s = float(std::sqrt(slope)), sigma_c = float(std::sqrt(offset));
    }
    out.noise.sigma_s[std::size_t(c)] = sigma_s;
    out.noise.sigma_c[std::size_t(c)] = sigma_c;
    const std::vector<Threshold>& th = fitted.fit;
    double r2 = 0;
    for (std::size_t i = 0; i < th.size(); ++i) {
      out.levels[std::size_t(c)].push_back({fitted.level[i] - 0.5, th[i].tau, th[i].variance, int(th[i].count)});
      const double pred = std::max(1e-30, slope * th[i].tau + offset);
      r2 += std::pow((th[i].variance - pred) / pred, 2);
    }
    out.rms_relative_residual[std::size_t(c)] = std::sqrt(r2 / double(th.size()));
  }
  return out;
}

}  // namespace hdrf::radiometry
