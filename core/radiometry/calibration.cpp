#include "radiometry/calibration.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <tuple>
#include <random>
#include <sstream>

#include "common/error.h"

namespace hdrf::radiometry {

namespace {

std::uint8_t Level(const Rgb8& p, int c) { return c == 0 ? p.r : (c == 1 ? p.g : p.b); }
bool Clipped(int z, ClipLevels clip) { return z < clip.lo || z > clip.hi; }

// Debevec's hat weight, zero where clipped, with a floor of 20 % of its peak so that the
// data (not the smoothness prior) shapes steep knees near saturation.
double Hat(int z, ClipLevels clip) {
  if (Clipped(z, clip)) return 0;
  const double hat = z <= 127 ? double(z - clip.lo + 1) : double(clip.hi - z + 1);
  return std::max(hat, 25.0);
}

struct Groups {
  std::vector<double> exposure;           // distinct, ascending
  std::vector<std::vector<int>> images;   // image indices per exposure
};

Groups GroupByExposure(const Sweep& s) {
  std::map<double, std::vector<int>> m;
  for (std::size_t i = 0; i < s.images.size(); ++i) m[s.exposure_ms[i]].push_back(int(i));
  Groups g;
  for (auto& [e, v] : m) {
    g.exposure.push_back(e);
    g.images.push_back(v);
  }
  return g;
}

// Pixel locations for fitting, stratified by the level of a middle exposure so that dark
// and bright parts of the curve both get samples; only pixels unclipped in >= 2 exposures.
std::vector<std::size_t> SamplePixels(const Sweep& s, const Groups& g, int c, int count,
                                      ClipLevels clip) {
  const std::size_t n = s.images[0].size();
  const ColorImage& mid = s.images[std::size_t(g.images[g.images.size() / 2][0])];
  std::vector<std::vector<std::size_t>> buckets(32);
  for (std::size_t p = 0; p < n; ++p) {
    int usable = 0;
    for (const auto& grp : g.images) usable += !Clipped(Level(s.images[std::size_t(grp[0])][p], c), clip);
    if (usable >= 2) buckets[Level(mid[p], c) / 8].push_back(p);
  }
  std::mt19937 rng(1234u + unsigned(c));
  std::vector<std::size_t> out;
  std::size_t non_empty = 0;
  for (auto& b : buckets) non_empty += !b.empty();
  if (!non_empty) return out;
  const std::size_t per = std::max<std::size_t>(1, std::size_t(count) / non_empty);
  for (auto& b : buckets) {
    std::shuffle(b.begin(), b.end(), rng);
    for (std::size_t k = 0; k < std::min(per, b.size()); ++k) out.push_back(b[k]);
  }
  return out;
}

ResponseFit Finish(ResponseFit fit, const Sweep& s, const Groups& g, ClipLevels clip) {
  EnforceMonotonic(fit.inverse);
  // Residual: ln(f^-1(I)/t) against the per-pixel mean of the same over the sweep.
  for (int c = 0; c < 3; ++c) {
    const auto px = SamplePixels(s, g, c, 2000, clip);
    double sum2 = 0;
    long n = 0;
    for (std::size_t p : px) {
      std::vector<double> v;
      for (std::size_t i = 0; i < s.images.size(); ++i) {
        const int z = Level(s.images[i][p], c);
        if (!Clipped(z, clip) && fit.inverse.table[c][z] > 0)
          v.push_back(std::log(fit.inverse.table[c][z] / s.exposure_ms[i]));
      }
      if (v.size() < 2) continue;
      const double m = std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
      for (double x : v) sum2 += (x - m) * (x - m);
      n += long(v.size());
    }
    fit.rms_log_residual[c] = n ? std::sqrt(sum2 / double(n)) : NAN;
    fit.samples_used[c] = int(px.size());
  }
  return fit;
}

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

}  // namespace

void CheckSweep(const Sweep& s) {
  const Groups g = GroupByExposure(s);
  if (s.images.empty()) throw Error(s.source + ": the sweep has no frames");
  if (s.images.size() != s.exposure_ms.size())
    throw Error(s.source + ": every frame needs an exposure (exposure.txt)");
  for (double e : s.exposure_ms)
    if (!(e > 0)) throw Error(s.source + ": exposures must be positive");
  if (g.exposure.size() < 2) {
    std::ostringstream os;
    os << s.source << ": the sweep has a single exposure (" << g.exposure[0]
       << " ms); calibration needs at least 2 distinct exposures, ideally 5 or more an "
          "f-stop apart";
    throw Error(os.str());
  }
  for (const auto& im : s.images)
    if (im.width() != s.images[0].width() || im.height() != s.images[0].height())
      throw Error(s.source + ": frames of different sizes");
  const ClipLevels clip;
  // Usable pixels: unclipped in at least two exposures (any channel).
  std::size_t usable = 0;
  const std::size_t n = s.images[0].size();
  for (std::size_t p = 0; p < n; p += 7) {
    int count = 0;
    for (const auto& grp : g.images) {
      const Rgb8 v = s.images[std::size_t(grp[0])][p];
      count += !Clipped(v.g, clip);
    }
    usable += count >= 2;
  }
  if (usable * 7 < 200)
    throw Error(s.source + ": almost every pixel is clipped (saturated or black) in all but one "
                           "exposure; use a scene with mid-tones and a wider exposure range");
  // A camera or scene that moved: the brightness order of image regions must be preserved
  // between exposures (the response is monotonic). Judged on means of 4 x 4 pixel blocks:
  // near black a steep response turns sensor noise into many levels (DoRF 159: +-10
  // levels), and single pixels then swap order with no motion at all.
  constexpr int kBlock = 4;
  const int bw = s.images[0].width() / kBlock, bh = s.images[0].height() / kBlock;
  // Block pairs count when 8 levels apart in both frames. Over all 201 DoRF curves with
  // no motion at most 0.7 % of them swap order; a 9-pixel shift swaps 18 %.
  constexpr float kMargin = 8.f;
  auto block_means = [&](const ColorImage& im) {
    std::vector<std::array<float, 3>> m(std::size_t(bw) * std::size_t(bh));
    for (int by = 0; by < bh; ++by)
      for (int bx = 0; bx < bw; ++bx)
        for (int c = 0; c < 3; ++c) {
          float sum = 0;
          bool clipped = false;
          for (int y = 0; y < kBlock; ++y)
            for (int x = 0; x < kBlock; ++x) {
              const int z = Level(im(bx * kBlock + x, by * kBlock + y), c);
              clipped |= Clipped(z, clip);
              sum += float(z);
            }
          m[std::size_t(by * bw + bx)][std::size_t(c)] = clipped ? NAN : sum / (kBlock * kBlock);
        }
    return m;
  };
  if (bw * bh >= 16) {
    std::mt19937 rng(99);
    std::uniform_int_distribution<std::size_t> pick(0, std::size_t(bw) * std::size_t(bh) - 1);
    // Judged per pair of consecutive exposures, so one move in a long sweep is not diluted.
    std::vector<std::array<float, 3>> next = block_means(s.images[std::size_t(g.images[0][0])]);
    for (std::size_t k = 0; k + 1 < g.images.size(); ++k) {
      const auto a = std::move(next);
      next = block_means(s.images[std::size_t(g.images[k + 1][0])]);
      const auto& b = next;
      long considered = 0, violations = 0;
      for (int t = 0; t < 20000; ++t) {
        const std::size_t p = pick(rng), q = pick(rng);
        for (std::size_t c = 0; c < 3; ++c) {
          const float ap = a[p][c], aq = a[q][c], bp = b[p][c], bq = b[q][c];
          if (std::isnan(ap) || std::isnan(aq) || std::isnan(bp) || std::isnan(bq)) continue;
          if (std::abs(ap - aq) <= kMargin || std::abs(bp - bq) <= kMargin) continue;
          ++considered;
          violations += (ap > aq) != (bp > bq);
        }
      }
      if (considered > 200 && double(violations) / double(considered) > 0.05) {
        std::ostringstream os;
        os << s.source << ": the camera or the scene moved during the sweep (between "
           << g.exposure[k] << " and " << g.exposure[k + 1] << " ms, "
           << int(100.0 * double(violations) / double(considered))
           << " % of image regions change brightness order); a sweep needs a static camera and a "
              "static scene";
        throw Error(os.str());
      }
    }
  }
}

void ScaleToUnitAt128(InverseResponse& r) {
  for (int c = 0; c < 3; ++c) {
    const float s = r.table[c][128];
    if (s > 0)
      for (float& v : r.table[c]) v /= s;
  }
}

double ScaleOnto(const InverseResponse& est, const InverseResponse& ref, int c, int lo, int hi) {
  double num = 0, den = 0;
  for (int i = lo; i <= hi; ++i) {
    num += double(est.table[c][i]) * ref.table[c][i];
    den += double(est.table[c][i]) * est.table[c][i];
  }
  return den > 0 ? num / den : 1.0;
}

void EnforceMonotonic(InverseResponse& r) {
  for (int c = 0; c < 3; ++c) {
    // Pool adjacent violators: blocks of (mean, weight).
    std::vector<double> mean;
    std::vector<int> len;
    for (int i = 0; i < kLevels; ++i) {
      mean.push_back(r.table[c][i]);
      len.push_back(1);
      while (mean.size() > 1 && mean[mean.size() - 2] > mean.back()) {
        const double m = (mean[mean.size() - 2] * len[len.size() - 2] + mean.back() * len.back()) /
                         double(len[len.size() - 2] + len.back());
        len[len.size() - 2] += len.back();
        mean[mean.size() - 2] = m;
        mean.pop_back();
        len.pop_back();
      }
    }
    int i = 0;
    for (std::size_t b = 0; b < mean.size(); ++b)
      for (int k = 0; k < len[b]; ++k) r.table[c][i++] = float(std::max(0.0, mean[b]));
  }
  ScaleToUnitAt128(r);
}

ResponseFit FitDebevec(const Sweep& s, const DebevecOptions& o) {
  CheckSweep(s);
  const Groups g = GroupByExposure(s);
  ResponseFit fit;
  fit.method = "debevec";
  for (int c = 0; c < 3; ++c) {
    const auto px = SamplePixels(s, g, c, o.samples, o.clip);
    const int N = int(px.size());
    if (N < 10) throw Error(s.source + ": too few usable pixels in channel " + std::to_string(c));
    // Normal equations of  w (g(z) - lnE_i) = w ln t  and  lambda w_s (g(z-1) - 2 g(z) + g(z+1)) = 0,
    // with the diagonal lnE block eliminated (Schur complement): a 256 x 256 system.
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(256, 256);
    Eigen::VectorXd rg = Eigen::VectorXd::Zero(256);
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(256, N);
    Eigen::VectorXd D = Eigen::VectorXd::Zero(N), rE = Eigen::VectorXd::Zero(N);
    for (int i = 0; i < N; ++i)
      for (std::size_t j = 0; j < s.images.size(); ++j) {
        const int z = Level(s.images[j][px[std::size_t(i)]], c);
        const double w = Hat(z, o.clip);
        if (w <= 0) continue;
        const double w2 = w * w, lt = std::log(s.exposure_ms[j]);
        G(z, z) += w2;
        B(z, i) -= w2;
        D(i) += w2;
        rg(z) += w2 * lt;
        rE(i) -= w2 * lt;
      }
    for (int z = 1; z < 255; ++z) {
      const double w = o.lambda * (Hat(z, {0, 255}) + 1.0);
      const double w2 = w * w;
      const int idx[3] = {z - 1, z, z + 1};
      const double coef[3] = {1, -2, 1};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) G(idx[a], idx[b]) += w2 * coef[a] * coef[b];
    }
    G(128, 128) += 1e8;  // g(128) = 0: f^-1(128) = 1
    for (int i = 0; i < N; ++i) {
      if (D(i) <= 0) {
        D(i) = 1;  // a sample with no usable observation: lnE free, decoupled
        continue;
      }
    }
    const Eigen::MatrixXd BDinv = B * D.cwiseInverse().asDiagonal();
    const Eigen::MatrixXd S = G - BDinv * B.transpose();
    const Eigen::VectorXd rhs = rg - BDinv * rE;
    const Eigen::VectorXd gz = S.ldlt().solve(rhs);
    for (int z = 0; z < 256; ++z) fit.inverse.table[c][z] = float(std::exp(gz(z)));
  }
  RefineOnThresholds(s, g, fit.inverse, o.threshold_passes, o.clip);
  return Finish(fit, s, g, o.clip);
}

ResponseFit FitRobertson(const Sweep& s, const RobertsonOptions& o) {
  CheckSweep(s);
  const Groups g = GroupByExposure(s);
  ResponseFit fit;
  fit.method = "robertson";
  auto weight = [&](int z) {
    if (Clipped(z, o.clip)) return 0.0;
    const double d = (z - 127.5) / 127.5;
    return std::exp(-4.0 * d * d);
  };
  for (int c = 0; c < 3; ++c) {
    const auto px = SamplePixels(s, g, c, o.samples, o.clip);
    const std::size_t N = px.size(), J = s.images.size();
    if (N < 10) throw Error(s.source + ": too few usable pixels in channel " + std::to_string(c));
    std::vector<std::uint8_t> Z(N * J);
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = 0; j < J; ++j) Z[i * J + j] = Level(s.images[j][px[i]], c);
    std::array<double, 256> gz{};
    for (int z = 0; z < 256; ++z) gz[std::size_t(z)] = std::max(1e-3, z / 128.0);
    std::vector<double> E(N);
    for (int it = 0; it < o.iterations; ++it) {
      for (std::size_t i = 0; i < N; ++i) {
        double num = 0, den = 0;
        for (std::size_t j = 0; j < J; ++j) {
          const int z = Z[i * J + j];
          const double w = weight(z), t = s.exposure_ms[j];
          num += w * gz[std::size_t(z)] * t;
          den += w * t * t;
        }
        E[i] = den > 0 ? num / den : 0;
      }
      std::array<double, 256> sum{}, cnt{};
      for (std::size_t i = 0; i < N; ++i)
        for (std::size_t j = 0; j < J; ++j) {
          const int z = Z[i * J + j];
          if (Clipped(z, o.clip) || E[i] <= 0) continue;
          sum[std::size_t(z)] += E[i] * s.exposure_ms[j];
          cnt[std::size_t(z)] += 1;
        }
      // M-step: the mean of E t over the observations of each level, with a weak penalty on
      // the second difference (o.smoothness times the mean count per level).
      double total = 0;
      for (double n : cnt) total += n;
      const double lambda = o.smoothness * total / 256.0;
      // A pentadiagonal system: a sparse factorisation, not a dense 256 x 256 one per iteration.
      std::vector<Eigen::Triplet<double>> entries;
      Eigen::VectorXd b(256);
      for (int z = 0; z < 256; ++z) {
        entries.emplace_back(z, z, cnt[std::size_t(z)]);
        b(z) = sum[std::size_t(z)];
      }
      for (int z = 1; z < 255; ++z) {
        const int idx[3] = {z - 1, z, z + 1};
        const double coef[3] = {1, -2, 1};
        for (int u = 0; u < 3; ++u)
          for (int v = 0; v < 3; ++v) entries.emplace_back(idx[u], idx[v], lambda * coef[u] * coef[v]);
      }
      Eigen::SparseMatrix<double> A(256, 256);
      A.setFromTriplets(entries.begin(), entries.end());  // duplicates are summed
      const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
      const Eigen::VectorXd sol = ldlt.solve(b);
      for (int z = 0; z < 256; ++z)
        if (cnt[std::size_t(z)] > 0) gz[std::size_t(z)] = std::max(1e-9, sol(z));
      const double s128 = gz[128];
      if (s128 > 0)
        for (double& v : gz) v /= s128;
    }
    // Levels never observed (clipped ends): extend with the slope of log g near the ends.
    int first = 0, last = 255;
    while (first < 255 && Clipped(first, o.clip)) ++first;
    while (last > 0 && Clipped(last, o.clip)) --last;
    const double slope_lo = std::log(gz[std::size_t(first + 4)] / gz[std::size_t(first)]) / 4.0;
    const double slope_hi = std::log(gz[std::size_t(last)] / gz[std::size_t(last - 4)]) / 4.0;
    for (int z = first - 1; z >= 0; --z) gz[std::size_t(z)] = gz[std::size_t(z + 1)] * std::exp(-slope_lo);
    for (int z = last + 1; z < 256; ++z) gz[std::size_t(z)] = gz[std::size_t(z - 1)] * std::exp(slope_hi);
    for (int z = 0; z < 256; ++z) fit.inverse.table[c][z] = float(gz[std::size_t(z)]);
  }
  RefineOnThresholds(s, g, fit.inverse, o.threshold_passes, o.clip);
  return Finish(fit, s, g, o.clip);
}

EmorBasis EmorBasis::Load(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, std::filesystem::exists(file) ? "cannot be opened" : "file is missing");
  EmorBasis b;
  std::vector<std::vector<double>> blocks;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find('=') != std::string::npos) {
      blocks.emplace_back();
      continue;
    }
    if (blocks.empty()) throw InputError(file, line_no, "data before the first 'name =' header");
    std::istringstream ss(line);
    double v;
    while (ss >> v) blocks.back().push_back(v);
  }
  if (blocks.size() < 3) throw InputError(file, "expected B, g0 and hinv blocks, found " + std::to_string(blocks.size()));
  for (std::size_t k = 0; k < blocks.size(); ++k)
    if (blocks[k].size() != 1024)
      throw InputError(file, "block " + std::to_string(k + 1) + " has " +
                                 std::to_string(blocks[k].size()) + " values, expected 1024");
  b.g0 = blocks[1];
  b.h.assign(blocks.begin() + 2, blocks.end());
  return b;
}

ResponseFit FitEmor(const Sweep& s, const EmorBasis& basis, const EmorOptions& o) {
  CheckSweep(s);
  if (o.components < 1 || o.components > int(basis.h.size()))
    throw SettingError("--emor-components", "must be between 1 and " + std::to_string(basis.h.size()));
  const Groups g = GroupByExposure(s);
  const int K = o.components;
  // Basis values at the 256 levels (B = z / 255 on the 1024-sample grid).
  auto at = [](const std::vector<double>& v, int z) {
    const double x = z * 1023.0 / 255.0;
    const int i = std::min(1022, int(x));
    return v[std::size_t(i)] + (v[std::size_t(i + 1)] - v[std::size_t(i)]) * (x - i);
  };
  std::vector<double> g0(256);
  std::vector<std::vector<double>> h(std::size_t(K), std::vector<double>(256));
  for (int z = 0; z < 256; ++z) {
    g0[std::size_t(z)] = at(basis.g0, z);
    for (int k = 0; k < K; ++k) h[std::size_t(k)][std::size_t(z)] = at(basis.h[std::size_t(k)], z);
  }
  // The free-form Debevec curve of the sweep, projected onto the basis by least squares over
  // the unclipped levels with a free scale: a g_D(z) = g0(z) + sum c_n h_n(z), unknowns a, c.
  DebevecOptions dopt;
  dopt.clip = o.clip;
  dopt.threshold_passes = o.threshold_passes;
  const ResponseFit start = FitDebevec(s, dopt);
  ResponseFit fit;
  fit.method = "emor";
  for (int c = 0; c < 3; ++c) {
    const auto& d = start.inverse.table[c];
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(K + 1, K + 1);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(K + 1);
    for (int z = o.clip.lo; z <= o.clip.hi; ++z) {
      Eigen::VectorXd row(K + 1);
      row(0) = d[std::size_t(z)];
      for (int n = 0; n < K; ++n) row(n + 1) = -h[std::size_t(n)][std::size_t(z)];
      P += row * row.transpose();
      q += row * g0[std::size_t(z)];
    }
    const Eigen::VectorXd x = P.ldlt().solve(q);
    for (int z = 0; z < 256; ++z) {
      double v = g0[std::size_t(z)];
      for (int n = 0; n < K; ++n) v += x(n + 1) * h[std::size_t(n)][std::size_t(z)];
      fit.inverse.table[c][z] = float(std::max(0.0, v));
    }
  }
  fit = Finish(fit, s, g, o.clip);
  for (int c = 0; c < 3; ++c) {
    const auto& e = fit.inverse.table[c];
    const auto& d = start.inverse.table[c];
    const double scale = ScaleOnto(fit.inverse, start.inverse, c, 5, 250);
    const double range = std::max(1e-12, double(d[255] - d[0]));
    for (int z = 5; z <= 250; ++z) {
      const double gap = std::abs(scale * e[z] - d[z]) / range;
      if (gap > fit.basis_gap[c]) fit.basis_gap[c] = gap, fit.basis_gap_level[c] = z;
    }
  }
  return fit;
}

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

RadianceImage MergeHdr(const Sweep& s, const InverseResponse& inv, const NoiseModel& noise,
                       ClipLevels clip) {
  // Per level and channel: variance of R (noise model plus quantisation).
  LevelTable var_r{};
  for (int c = 0; c < 3; ++c)
    for (int z = 0; z < kLevels; ++z) {
      const int lo = std::max(0, z - 1), hi = std::min(kLevels - 1, z + 1);
      const double q = (inv.table[c][hi] - inv.table[c][lo]) / double(hi - lo);
      const double R = inv.table[c][z];
      var_r[c][z] = float(R * noise.sigma_s[c] * noise.sigma_s[c] +
                          noise.sigma_c[c] * noise.sigma_c[c] + q * q / 12.0);
    }
  const std::size_t n = s.images[0].size();
  RadianceImage out(s.images[0].width(), s.images[0].height());
  std::size_t shortest = 0, longest = 0;
  for (std::size_t j = 0; j < s.images.size(); ++j) {
    if (s.exposure_ms[j] < s.exposure_ms[shortest]) shortest = j;
    if (s.exposure_ms[j] > s.exposure_ms[longest]) longest = j;
  }
#pragma omp parallel for schedule(static)
  for (long pl = 0; pl < long(n); ++pl) {
    const std::size_t p = std::size_t(pl);
    float v[3];
    for (int c = 0; c < 3; ++c) {
      double num = 0, den = 0;
      bool any_bright = false;
      for (std::size_t j = 0; j < s.images.size(); ++j) {
        const int z = Level(s.images[j][p], c);
        if (Clipped(z, clip)) {
          any_bright |= z > clip.hi;
          continue;
        }
        const double t = s.exposure_ms[j];
        const double w = t * t / std::max(1e-20, double(var_r[c][z]));
        num += w * inv.table[c][z] / t;
        den += w;
      }
      if (den > 0) {
        v[c] = float(num / den);
      } else {
        const std::size_t j = any_bright ? shortest : longest;
        v[c] = float(inv.table[c][Level(s.images[j][p], c)] / s.exposure_ms[j]);
      }
    }
    out[p] = {v[0], v[1], v[2]};
  }
  return out;
}

std::vector<ExposureConsistency> MergeConsistency(const Sweep& s, const InverseResponse& inv,
                                                  const RadianceImage& merged, ClipLevels clip) {
  const Groups g = GroupByExposure(s);
  std::vector<ExposureConsistency> out;
  for (std::size_t k = 0; k < g.exposure.size(); ++k) {
    std::vector<float> d;
    const ColorImage& im = s.images[std::size_t(g.images[k][0])];
    for (std::size_t p = 0; p < im.size(); p += 3)
      for (int c = 0; c < 3; ++c) {
        const int z = Level(im[p], c);
        const float L = c == 0 ? merged[p].x : (c == 1 ? merged[p].y : merged[p].z);
        if (z < std::max(32, clip.lo) || z > std::min(224, clip.hi) || !(L > 0)) continue;
        d.push_back(std::abs(std::log2(float(inv.table[c][z] / g.exposure[k]) / L)));
      }
    double med = NAN;
    if (!d.empty()) {
      std::nth_element(d.begin(), d.begin() + long(d.size() / 2), d.end());
      med = d[d.size() / 2];
    }
    out.push_back({g.exposure[k], med, long(d.size())});
  }
  return out;
}

}  // namespace hdrf::radiometry
