#include "tonemap/mantiuk08/mantiuk08.h"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error.h"
#include "common/image_view.h"
#include "common/parallel.h"

namespace hdrf::tonemap::m08 {

double DisplayModel::Offset() const { return black + reflectivity / std::numbers::pi * ambient; }

void DisplayModel::Check() const {
  if (!(gamma >= 1 && gamma <= 4)) throw SettingError("gamma", "display gamma must be within [1, 4]");
  if (!(black > 0 && peak > black)) throw SettingError("peak", "the peak luminance must exceed the black level (> 0)");
  if (!(reflectivity >= 0 && ambient >= 0)) throw SettingError("ambient", "reflectivity and ambient light cannot be negative");
}

void Options::Check() const {
  display.Check();
  if (!(ppd >= 1 && ppd <= 200)) throw SettingError("ppd", "pixels per degree must be within [1, 200]");
  if (!(contrast > 0)) throw SettingError("contrast", "the contrast enhancement must be positive");
  if (!(saturation >= 0 && saturation <= 2)) throw SettingError("saturation", "the saturation must be within [0, 2]");
  if (!(temporal_cutoff > 0)) throw SettingError("temporal_hz", "the cut-off must be positive");
  if (!(hold_stops >= 0 && hold_stops <= 4)) throw SettingError("hold", "the brightness hold must be within [0, 4] stops");
  if (!(hold_cutoff > 0)) throw SettingError("hold_hz", "the brightness adaptation's cut-off must be positive");
}

int BandCount(double ppd) {
  int b = 0;
  while (b < kMaxBands - 1 && 0.5 * ppd / double(1 << b) > 3) ++b;
  return b + 1;
}

namespace {

double BandFrequency(double ppd, int b) { return 0.5 * ppd / double(1 << b); }

// Daly's contrast sensitivity function (cycles per degree, adapting luminance cd/m^2),
// foveal, for an image of 1 square degree, at the viewing distance.
double CsfDaly(double rho, double lum, double distance) {
  if (rho == 0) return 0;
  constexpr double kPeak = 250, kEps = 0.9, kOblique = 0.78, kImageSize = 1;
  const double a = 0.801 * std::pow(1 + 0.7 / lum, -0.2);
  const double b = 0.3 * std::pow(1 + 100 / lum, 0.15);
  auto s = [&](double r) {
    const double b1 = b * kEps * r;
    return std::pow(std::pow(3.23 * std::pow(r * r * kImageSize, -0.3), 5.0) + 1, -0.2) * a * kEps * r *
           std::exp(-b1) * std::sqrt(1 + 0.06 * std::exp(b1));
  };
  const double accommodation = 0.856 * std::pow(distance, 0.14);
  const double orientation = (1 - kOblique) / 2 + (1 + kOblique) / 2;  // at angle 0
  return std::min(s(rho), s(rho / (accommodation * orientation))) * kPeak;
}

struct Vision {
  bool contrast_masking, luminance_masking, csf;
  double distance;
  double Sensitivity(double rho, double lum) const {
    return CsfDaly(csf ? rho : 4.0, luminance_masking ? lum : 1000.0, distance);
  }
  // Response to a log10 contrast at a sensitivity: with contrast masking, the transducer
  // of Mantiuk et al. (Weber contrast scaled by the sensitivity, compressed); without, linear.
  double Transducer(double c, double sensitivity) const {
    if (!contrast_masking) return c * sensitivity;
    constexpr double kQ = 3, kA = 3.291, kB = 3.433, kE = 0.8, kK = 0.2599;
    const double sc = sensitivity * (std::pow(10.0, std::abs(c)) - 1);
    const double r = kA * (std::cbrt(1 + std::pow(sc, kQ)) - 1) / (kK * std::pow(kB + sc, kE));
    return c < 0 ? -r : r;
  }
};

// min 0.5 x'Hx + f'x  subject to  x >= 0, sum(x) <= total: a primal active-set method,
// started from `x` (feasible). The problems are small (one variable per curve segment).
void SolveQp(const Eigen::MatrixXd& h_in, const Eigen::VectorXd& f_in, double total, Eigen::VectorXd& x) {
  const int n = int(x.size());
  // Scaled so that the largest diagonal entry is 1 (the counts make H span many decades).
  const double scale = 1 / std::max(1e-300, h_in.diagonal().cwiseAbs().maxCoeff());
  const Eigen::MatrixXd h = h_in * scale;
  const Eigen::VectorXd f = f_in * scale;
  std::vector<char> at_zero(std::size_t(n), 0);
  for (int i = 0; i < n; ++i) at_zero[std::size_t(i)] = x[i] <= 0;
  bool sum_active = x.sum() >= total * (1 - 1e-12);
  const double ridge = 1e-10;
  for (int it = 0; it < 10 * n + 50; ++it) {
    std::vector<int> free;
    for (int i = 0; i < n; ++i)
      if (!at_zero[std::size_t(i)]) free.push_back(i);
    const int m = int(free.size());
    const int k = m + (sum_active ? 1 : 0);
    Eigen::VectorXd target = x;
    double mu = 0;
    if (m > 0) {
      Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(k, k);
      Eigen::VectorXd rhs(k);
      for (int a = 0; a < m; ++a) {
        for (int b = 0; b < m; ++b) kkt(a, b) = h(free[std::size_t(a)], free[std::size_t(b)]);
        kkt(a, a) += ridge;
        rhs[a] = -f[free[std::size_t(a)]];
      }
      if (sum_active) {
        for (int a = 0; a < m; ++a) kkt(a, m) = kkt(m, a) = 1;
        rhs[m] = total;
      }
      const Eigen::VectorXd sol = kkt.partialPivLu().solve(rhs);
      target.setZero();
      for (int a = 0; a < m; ++a) target[free[std::size_t(a)]] = sol[a];
      if (sum_active) mu = sol[m];
    } else {
      target.setZero();
    }
    const Eigen::VectorXd p = target - x;
    if (p.cwiseAbs().maxCoeff() <= 1e-12 * std::max(1.0, total)) {
      // At the subspace minimum: drop the constraint with the most negative multiplier.
      const Eigen::VectorXd g = h * x + f;
      int drop = -1;
      double worst = -1e-12 * std::max(1.0, g.cwiseAbs().maxCoeff());
      for (int i = 0; i < n; ++i)
        if (at_zero[std::size_t(i)]) {
          const double lambda = g[i] + (sum_active ? mu : 0.0);
          if (lambda < worst) worst = lambda, drop = i;
        }
      // The sum constraint's multiplier: stationarity H x + f + mu 1 = 0 on the free set, so
      // mu = -(Hx + f)_i there; a negative mu means the sum wants to shrink.
      if (sum_active && mu < worst) {
        sum_active = false;
        continue;
      }
      if (drop < 0) return;
      at_zero[std::size_t(drop)] = 0;
      continue;
    }
    double alpha = 1;
    int block = -1;
    bool block_sum = false;
    for (int i = 0; i < n; ++i)
      if (!at_zero[std::size_t(i)] && p[i] < 0) {
        const double a = -x[i] / p[i];
        if (a < alpha) alpha = a, block = i, block_sum = false;
      }
    if (!sum_active && p.sum() > 0) {
      const double a = (total - x.sum()) / p.sum();
      if (a < alpha) alpha = a, block = -1, block_sum = true;
    }
    x += std::max(0.0, alpha) * p;
    if (block >= 0) {
      at_zero[std::size_t(block)] = 1;
      x[block] = 0;
    }
    if (block_sum) sum_active = true;
  }
}

// One row of the least-squares problem: a contrast between two nodes, i.e. the sum of the
// curve variables [first, last), to be shown with the response `target`.
struct Row {
  int first, last;   // variable range
  double weight;     // how many pixels show this contrast (or an anchoring weight)
  double target;     // response the scene's contrast produces
  int band;          // for the display-side sensitivity
  int background;    // node whose display luminance sets that sensitivity
};

// The curve from the variables: flat below the first variable, each variable's rise spread
// evenly over its segments, flat after the last; the top sits at the display's maximum.
ToneCurve CurveFromVariables(const Eigen::VectorXd& x, const std::vector<int>& var_first,
                             const std::vector<int>& var_len, double y_min, double y_max) {
  std::array<double, kNodes - 1> rise{};
  for (std::size_t v = 0; v < var_first.size(); ++v)
    for (int s = 0; s < var_len[v]; ++s) rise[std::size_t(var_first[v] + s)] = x[int(v)] / var_len[v];
  ToneCurve y{};
  const double range = y_max - y_min;
  y[0] = y_min + (range - x.sum());
  for (int i = 0; i + 1 < kNodes; ++i) y[std::size_t(i + 1)] = y[std::size_t(i)] + rise[std::size_t(i)];
  return y;
}

}  // namespace

float LuminanceFloor(const RadianceImage& rgb) {
  float lo = kMaxLum;
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const float l = Luminance(rgb[i]);
    if (l > 0 && l < lo) lo = l;
  }
  return std::max(lo, kMinLum);
}

Density ComputeDensity(const RadianceImage& rgb, float floor, int bands) {
  const int w = rgb.width(), h = rgb.height();
  Density d;
  d.bands = bands;
  d.count.assign(std::size_t(bands) * kNodes * kContrastBins, 0.0);
  if (rgb.empty()) return d;
  Image<float> high(w, h), low(w, h), tmp(w, h);
  Image<std::uint8_t> valid(w, h);
  // Pixels with no data (all zero or not finite) are left out of the counts; for the
  // low-pass they take the mean log luminance of the rest (a neutral surround).
  double sum = 0;
  long n_valid = 0;
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const Float3 c = rgb[i];
    const float l = Luminance(c);
    const bool ok = std::isfinite(l) && !(c.x == 0 && c.y == 0 && c.z == 0);
    valid[i] = ok;
    high[i] = ClampedLog10(ok ? l : 0.f, floor);
    if (ok) sum += high[i], ++n_valid;
  }
  if (n_valid == 0) return d;
  const float fill = float(sum / double(n_valid));
  for (std::size_t i = 0; i < rgb.size(); ++i)
    if (!valid[i]) high[i] = fill;
  const int threads = omp_get_max_threads();
  std::vector<std::vector<int>> local(std::size_t(threads), std::vector<int>(std::size_t(kNodes) * kContrastBins));
  for (int b = 0; b < bands; ++b) {
    const int step = 1 << b;
    ImageView<const float> hi = View(std::as_const(high));
    ImageView<float> tv = View(tmp), lv = View(low);
    par::ForEachPixel(par::Host{}, w, h, [=](int x, int y) { tv(x, y) = LowPassTap(hi, x, y, step, true); });
    ImageView<const float> tc = View(std::as_const(tmp));
    par::ForEachPixel(par::Host{}, w, h, [=](int x, int y) { lv(x, y) = LowPassTap(tc, x, y, step, false); });
    for (auto& l : local) std::fill(l.begin(), l.end(), 0);
    const float* hp = high.data();
    const float* lp = low.data();
    const std::uint8_t* vp = valid.data();
    const long n = long(high.size());
#pragma omp parallel
    {
      std::vector<int>& mine = local[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(static)
      for (long i = 0; i < n; ++i) {
        const int cell = vp[i] ? DensityCell(hp[i], lp[i]) : -1;
        if (cell >= 0) ++mine[std::size_t(cell)];
      }
    }
    for (int node = 0; node < kNodes; ++node)
      for (int g = 0; g < kContrastBins; ++g) {
        double s = 0;
        for (const auto& l : local) s += l[std::size_t(node * kContrastBins + g)];
        d.at(b, node, g) = s;
      }
    std::swap(high, low);
  }
  FinishDensity(d);
  return d;
}

void FinishDensity(Density& d) {
  d.total = 0;
  for (int b = 0; b < d.bands; ++b)
    for (int node = 0; node < kNodes; ++node) {
      if (d.at(b, node, kZeroBin) == 0) continue;
      bool contrast = false;
      for (int g = 0; g < kContrastBins; ++g) contrast |= g != kZeroBin && d.at(b, node, g) != 0;
      if (!contrast) {
        d.at(b, node, kZeroBin + 1) += 1;
        d.at(b, node, kZeroBin - 1) += 1;
      }
      for (int g = 0; g < kContrastBins; ++g)
        if (g != kZeroBin) d.total += d.at(b, node, g);
    }
}

ToneCurve OptimiseCurve(const Density& d, const Options& o, int* iterations) {
  const Vision vision{o.contrast_masking, o.luminance_masking, o.csf, o.viewing_distance};
  const double y_min = std::log10(o.display.MinLuminance()), y_max = std::log10(o.display.MaxLuminance());
  const double range = y_max - y_min;
  auto node_log = [](int i) { return double(kLogMin) + double(kStep) * i; };
  // Sensitivity per band over node luminance (for the display side, looked up at the curve's
  // display luminance).
  std::vector<std::array<double, kNodes>> csf(std::size_t(d.bands));
  for (int b = 0; b < d.bands; ++b)
    for (int i = 0; i < kNodes; ++i)
      csf[std::size_t(b)][std::size_t(i)] = vision.Sensitivity(BandFrequency(o.ppd, b), std::pow(10.0, node_log(i)));
  auto csf_at = [&](int b, double log_lum) {
    const double f = (log_lum - kLogMin) / kStep;
    const auto& t = csf[std::size_t(b)];
    if (f <= 0) return t[0];
    if (f >= kNodes - 1) return t[kNodes - 1];
    const int i = int(f);
    return t[std::size_t(i)] + (t[std::size_t(i + 1)] - t[std::size_t(i)]) * (f - i);
  };
  auto scene_sensitivity = [&](int b, int from) {
    return o.scene_adaptation > 0 ? vision.Sensitivity(BandFrequency(o.ppd, b), o.scene_adaptation)
                                  : csf_at(b, node_log(from));
  };

  // Contrasts present: node i against neighbour j = i + (bin - zero), j within the range
  // the histogram covers on the lower side and one short of it on the upper side.
  struct Pair {
    int b, i, j;
    double n;
  };
  std::vector<Pair> pairs;
  std::vector<char> used(kNodes - 1, 0);
  int lo = kNodes - 1, hi = 0;
  for (int b = 0; b < d.bands; ++b)
    for (int i = 0; i < kNodes; ++i)
      for (int j = std::max(0, i - kZeroBin); j < std::min(kNodes - 1, i + kZeroBin); ++j) {
        if (j == i) continue;
        const double n = d.at(b, i, j - i + kZeroBin);
        if (n == 0) continue;
        pairs.push_back({b, i, j, n});
        const int from = std::min(i, j), to = std::max(i, j);
        for (int s = from; s < to; ++s) used[std::size_t(s)] = 1;
        lo = std::min(lo, from);
        hi = std::max(hi, to - 1);
      }
  if (pairs.empty()) throw Error("mantiuk08: the image has no contrast to map (it is empty or flat)");

  // Variables: one per used segment in [lo, hi]; a run of unused segments (no contrast
  // spans it: disconnected parts of the histogram) shares one variable.
  std::vector<int> var_of(kNodes - 1, -1), var_first, var_len;
  for (int s = lo; s <= hi; ++s) {
    if (!used[std::size_t(s)] && s > lo && !used[std::size_t(s - 1)]) {
      var_of[std::size_t(s)] = var_of[std::size_t(s - 1)];
      ++var_len.back();
      continue;
    }
    var_of[std::size_t(s)] = int(var_first.size());
    var_first.push_back(s);
    var_len.push_back(1);
  }
  const int nv = int(var_first.size());
  std::vector<Row> rows;
  rows.reserve(pairs.size() + 8);
  for (const Pair& p : pairs) {
    const int from = std::min(p.i, p.j), to = std::max(p.i, p.j);
    const double target = vision.Transducer((node_log(to) - node_log(from)) * o.contrast, scene_sensitivity(p.b, from));
    rows.push_back({var_of[std::size_t(from)], var_of[std::size_t(to - 1)] + 1, p.n, target, p.b, p.i});
  }
  // Anchor each shared (unused) run so that the parts either side keep their relation.
  for (int v = 0; v < nv; ++v) {
    const int s = var_first[std::size_t(v)];
    if (used[std::size_t(s)]) continue;
    const int to = s + var_len[std::size_t(v)];
    const int band = d.bands - 1;
    const double sens = o.scene_adaptation > 0 ? vision.Sensitivity(BandFrequency(o.ppd, band), o.scene_adaptation)
                                               : csf_at(band, node_log(s));
    rows.push_back({v, v + 1, d.total * 0.1, vision.Transducer((node_log(to) - node_log(s)) * o.contrast, sens), band, to});
  }

  Eigen::VectorXd x = Eigen::VectorXd::Constant(nv, range / nv);
  Eigen::MatrixXd h(nv, nv);
  Eigen::VectorXd f(nv);
  std::vector<double> ranges(std::size_t(nv) * std::size_t(nv + 1));
  int it = 0;
  constexpr int kMaxIterations = 200;
  const double tolerance = kStep / 10.0;
  for (; it < (o.contrast_masking ? kMaxIterations : 1); ++it) {
    const ToneCurve y = CurveFromVariables(x, var_first, var_len, y_min, y_max);
    std::vector<double> prefix(std::size_t(nv) + 1, 0.0);
    for (int v = 0; v < nv; ++v) prefix[std::size_t(v + 1)] = prefix[std::size_t(v)] + x[v];
    // H = sum w K^2 a a', f = -sum w K B a, with a the indicator of [first, last): gather the
    // weights per range, then sum them into H by two cumulative passes.
    std::fill(ranges.begin(), ranges.end(), 0.0);
    f.setZero();
    std::vector<double> fr(std::size_t(nv) * std::size_t(nv + 1), 0.0);
    for (const Row& r : rows) {
      const double ax = prefix[std::size_t(r.last)] - prefix[std::size_t(r.first)];
      const double sens = csf_at(r.band, y[std::size_t(r.background)]);
      const double k = vision.Transducer(ax, sens) / (std::abs(ax) < 1e-4 ? 1.0 : ax);
      ranges[std::size_t(r.first) * std::size_t(nv + 1) + std::size_t(r.last)] += r.weight * k * k;
      fr[std::size_t(r.first) * std::size_t(nv + 1) + std::size_t(r.last)] += r.weight * k * r.target;
    }
    // cover[p][c] = sum over ranges starting at p that contain c (first = p <= c < last).
    Eigen::MatrixXd cover = Eigen::MatrixXd::Zero(nv, nv), fcover = Eigen::MatrixXd::Zero(nv, nv);
    for (int p = 0; p < nv; ++p) {
      double acc = 0, facc = 0;
      for (int last = nv; last > p; --last) {
        acc += ranges[std::size_t(p) * std::size_t(nv + 1) + std::size_t(last)];
        facc += fr[std::size_t(p) * std::size_t(nv + 1) + std::size_t(last)];
        if (last - 1 >= p) cover(p, last - 1) = acc, fcover(p, last - 1) = facc;
      }
    }
    // H[r][c] (r <= c) = sum over p <= r of cover[p][c].
    for (int c = 0; c < nv; ++c) {
      double acc = 0;
      for (int r = 0; r <= c; ++r) {
        acc += cover(r, c);
        h(r, c) = h(c, r) = acc;
      }
      double facc = 0;
      for (int p = 0; p <= c; ++p) facc += fcover(p, c);
      f[c] = -facc;
    }
    const Eigen::VectorXd before = x;
    SolveQp(h, f, range, x);
    if ((x - before).cwiseAbs().maxCoeff() <= tolerance) {
      ++it;
      break;
    }
  }
  if (iterations) *iterations = it;
  return CurveFromVariables(x, var_first, var_len, y_min, y_max);
}

CurveLut MakeLut(const ToneCurve& y, const Options& o, float floor) {
  CurveLut c{};
  for (int i = 0; i < kNodes; ++i) c.lum[i] = float(std::pow(10.0, y[std::size_t(i)]));
  // Colour correction (Mantiuk et al. 2009): saturation follows the curve's slope.
  constexpr double k1 = 1.48, k2 = 0.82;
  for (int i = 0; i + 1 < kNodes; ++i) {
    const double slope = std::max((y[std::size_t(i + 1)] - y[std::size_t(i)]) / kStep, 0.0);
    const double p = std::pow(slope, k2);
    c.sat[i] = float((1 + k1) * p / (1 + k1 * p) * o.saturation);
  }
  c.sat[kNodes - 1] = 1;
  c.floor = floor;
  c.offset = float(o.display.Offset());
  c.range = float(o.display.peak - o.display.black);
  return c;
}

ToneCurve CurveFilter::Update(const ToneCurve& curve, double t, double cutoff_hz, double y_min, double y_max) {
  if (t < 0) {  // a still
    started_ = false;
    return curve;
  }
  if (!started_ || t < last_t_) {  // the first frame, or time ran backwards (a new sequence)
    stage1_ = stage2_ = curve;
    started_ = true;
    last_t_ = t;
    return curve;
  }
  const double dt = t - last_t_;
  last_t_ = t;
  const double a = 1 - std::exp(-2 * std::numbers::pi * cutoff_hz * dt);
  ToneCurve out{};
  for (int i = 0; i < kNodes; ++i) {
    stage1_[std::size_t(i)] += a * (curve[std::size_t(i)] - stage1_[std::size_t(i)]);
    stage2_[std::size_t(i)] += a * (stage1_[std::size_t(i)] - stage2_[std::size_t(i)]);
    out[std::size_t(i)] = std::clamp(stage2_[std::size_t(i)], y_min, y_max);
  }
  return out;
}

std::array<double, kNodes> PixelHistogram(const Density& d) {
  std::array<double, kNodes> h{};
  if (d.bands == 0) return h;
  for (int node = 0; node < kNodes; ++node)
    for (int g = 0; g < kContrastBins; ++g) {
      const int own = std::clamp(node + g - kZeroBin, 0, kNodes - 1);
      h[std::size_t(own)] += d.at(0, node, g);
    }
  return h;
}

ToneCurve BrightnessHold::Update(const ToneCurve& curve, const std::array<double, kNodes>& pixels, double t,
                                 double cutoff_hz, double max_shift, double y_min, double y_max) {
  double total = 0, mean = 0;
  for (int i = 0; i < kNodes; ++i) total += pixels[std::size_t(i)], mean += pixels[std::size_t(i)] * curve[std::size_t(i)];
  shift_ = 0;
  if (t < 0) started_ = false;  // a still ends the hold
  if (t < 0 || total <= 0 || !(max_shift > 0)) return curve;  // an empty frame keeps it
  mean /= total;
  if (!started_ || t < last_t_) {
    stage1_ = stage2_ = mean;
    started_ = true;
    last_t_ = t;
    return curve;
  }
  const double a = 1 - std::exp(-2 * std::numbers::pi * cutoff_hz * (t - last_t_));
  last_t_ = t;
  stage1_ += a * (mean - stage1_);
  stage2_ += a * (stage1_ - stage2_);
  // The shift whose clamped curve has the held mean: the clamped mean grows monotonically
  // with the shift, so bisection within the allowed range finds it (or the range's end).
  auto shown = [&](double s) {
    double m = 0;
    for (int i = 0; i < kNodes; ++i) m += pixels[std::size_t(i)] * std::clamp(curve[std::size_t(i)] + s, y_min, y_max);
    return m / total;
  };
  double lo = -max_shift, hi = max_shift;
  if (shown(lo) >= stage2_) {
    hi = lo;
  } else if (shown(hi) <= stage2_) {
    lo = hi;
  } else {
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      (shown(mid) < stage2_ ? lo : hi) = mid;
    }
  }
  shift_ = 0.5 * (lo + hi);
  ToneCurve out{};
  for (int i = 0; i < kNodes; ++i) out[std::size_t(i)] = std::clamp(curve[std::size_t(i)] + shift_, y_min, y_max);
  return out;
}

}  // namespace hdrf::tonemap::m08
