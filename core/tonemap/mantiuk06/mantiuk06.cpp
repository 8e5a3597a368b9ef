#include "tonemap/mantiuk06/mantiuk06.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/parallel.h"

namespace hdrf::tonemap::m06 {

void Options::Check() const {
  if (!(contrast > 0 && contrast <= 1)) throw SettingError("contrast", "the contrast factor must be within (0, 1]");
  if (!(saturation >= 0 && saturation <= 2)) throw SettingError("saturation", "the saturation must be within [0, 2]");
  if (!(detail >= 0.5 && detail <= 10)) throw SettingError("detail", "the detail factor must be within [0.5, 10]");
  if (iterations < 1) throw SettingError("iterations", "at least one iteration is needed");
}

namespace {

// Just-noticeable differences per log10 unit of contrast: the inverse of the discrimination
// threshold, which is the detection threshold (1 % Weber contrast) for the smallest
// contrasts and grows as a power of the contrast above it.
double ThresholdAt(double g) {
  const double detect = std::log10(1.01);
  return std::max(detect, 0.038737 * std::pow(g, 0.537756));
}

Transducer BuildTransducer() {
  Transducer t{};
  // Response = integral of 1 / threshold, by Simpson's rule on 16 sub-steps per entry.
  t.response[0] = 0;
  for (int i = 1; i < kTableSize; ++i) {
    const double a = (i - 1) * double(kTableStep), b = i * double(kTableStep);
    constexpr int kSub = 16;
    const double h = (b - a) / kSub;
    double s = 1 / ThresholdAt(a) + 1 / ThresholdAt(b);
    for (int k = 1; k < kSub; ++k) s += (k % 2 ? 4 : 2) / ThresholdAt(a + k * h);
    t.response[i] = float(t.response[i - 1] + s * h / 3);
  }
  // Responses in units of the response to a 4 log10-unit contrast (10^4 : 1, the largest
  // contrast a scene is taken to show): equalisation maps contrasts onto [0, factor] of it.
  const double unit = t.response[int(4.0 / double(kTableStep))] +
                      (t.response[int(4.0 / double(kTableStep)) + 1] - t.response[int(4.0 / double(kTableStep))]) *
                          (4.0 / double(kTableStep) - int(4.0 / double(kTableStep)));
  for (float& r : t.response) r = float(r / unit);
  t.inverse_step = t.response[kTableSize - 1] / float(kTableSize - 1);
  int i = 0;
  for (int j = 0; j < kTableSize; ++j) {
    const float r = float(j) * t.inverse_step;
    while (i + 2 < kTableSize && t.response[i + 1] < r) ++i;
    const float r0 = t.response[i], r1 = t.response[i + 1];
    const float f = r1 > r0 ? std::clamp((r - r0) / (r1 - r0), 0.f, 1.f) : 0.f;
    t.inverse[j] = (float(i) + f) * kTableStep;
  }
  return t;
}

struct Level {
  int w = 0, h = 0;
  std::vector<float> value, gx, gy, wx, wy, sum;  // log lum, gradients, fit weights, divergence sum
  ImageView<float> V(std::vector<float>& v) { return {v.data(), w, h}; }
  ImageView<const float> C(const std::vector<float>& v) const { return {v.data(), w, h}; }
};

std::vector<Level> MakePyramid(int w, int h) {
  std::vector<Level> levels;
  while (w >= 3 && h >= 3) {
    Level l;
    l.w = w, l.h = h;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    for (auto* v : {&l.value, &l.gx, &l.gy, &l.wx, &l.wy, &l.sum}) v->assign(n, 0.f);
    levels.push_back(std::move(l));
    w /= 2, h /= 2;
  }
  return levels;
}

// value[0] given: fills the coarser levels' values by downsampling.
void DownsampleChain(std::vector<Level>& lv) {
  for (std::size_t k = 1; k < lv.size(); ++k) {
    ImageView<const float> fine = lv[k - 1].C(lv[k - 1].value);
    ImageView<float> out = lv[k].V(lv[k].value);
    const int ow = lv[k].w, oh = lv[k].h;
    par::ForEachPixel(par::Host{}, ow, oh, [=](int x, int y) { out(x, y) = Downsample(fine, ow, oh, x, y); });
  }
}

// sum[0] = sum over levels of (upsampled) divergence of (weights * gradients of value), or
// with `targets` the divergence of the stored target gradients (already weighted).
void DivergenceSum(std::vector<Level>& lv, bool targets) {
  for (int k = int(lv.size()) - 1; k >= 0; --k) {
    Level& l = lv[std::size_t(k)];
    ImageView<float> s = l.V(l.sum);
    if (!targets) {
      ImageView<const float> v = l.C(l.value), wx = l.C(l.wx), wy = l.C(l.wy);
      ImageView<float> gx = l.V(l.gx), gy = l.V(l.gy);
      par::ForEachPixel(par::Host{}, l.w, l.h, [=](int x, int y) {
        gx(x, y) = wx(x, y) * GradX(v, x, y);
        gy(x, y) = wy(x, y) * GradY(v, x, y);
      });
    }
    ImageView<const float> gx = l.C(l.gx), gy = l.C(l.gy);
    const bool coarsest = k + 1 == int(lv.size());
    ImageView<const float> coarse = coarsest ? ImageView<const float>{} : lv[std::size_t(k + 1)].C(lv[std::size_t(k + 1)].sum);
    const int w = l.w, h = l.h;
    par::ForEachPixel(par::Host{}, w, h, [=](int x, int y) {
      s(x, y) = Divergence(gx, gy, x, y) + (coarsest ? 0.f : Upsample(coarse, w, h, x, y));
    });
  }
}

double Dot(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0;
  const long n = long(a.size());
#pragma omp parallel for reduction(+ : s) schedule(static)
  for (long i = 0; i < n; ++i) s += double(a[std::size_t(i)]) * double(b[std::size_t(i)]);
  return s;
}

bool NoData(Float3 c) {
  return !(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) || (c.x == 0 && c.y == 0 && c.z == 0);
}

}  // namespace

// Value at quantile q of v (by a fine histogram, linear within a bin).
void Quantiles(const std::vector<float>& v, const std::vector<std::uint8_t>& valid, double q_lo, double q_hi, float* out_lo,
               float* out_hi) {
  float lo = 1e30f, hi = -1e30f;
  long n = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (valid[i]) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]), ++n;
  *out_lo = lo, *out_hi = hi;
  if (n == 0 || hi <= lo) return;
  constexpr int kBins = 16384;
  std::vector<long> hist(kBins, 0);
  const double scale = kBins / double(hi - lo);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (valid[i]) ++hist[std::size_t(std::clamp(int((v[i] - lo) * scale), 0, kBins - 1))];
  auto at = [&](double q) {
    const double target = q * double(n);
    double acc = 0;
    for (int b = 0; b < kBins; ++b) {
      const double next = acc + double(hist[std::size_t(b)]);
      if (next >= target && hist[std::size_t(b)] > 0) return float(lo + (b + (target - acc) / double(hist[std::size_t(b)])) / scale);
      acc = next;
    }
    return hi;
  };
  *out_lo = at(q_lo), *out_hi = at(q_hi);
}

float Quantile(const std::vector<float>& v, const std::vector<std::uint8_t>& valid, double q) {
  float a = 0, b = 0;
  Quantiles(v, valid, q, q, &a, &b);
  return a;
}

std::vector<float> EqualisationCdf(const std::vector<const std::vector<float>*>& gx,
                                   const std::vector<const std::vector<float>*>& gy, float* top_out) {
  float top = 0;
  double total = 0;
  for (std::size_t l = 0; l < gx.size(); ++l)
    for (std::size_t i = 0; i < gx[l]->size(); ++i) top = std::max(top, std::hypot((*gx[l])[i], (*gy[l])[i])), total += 1;
  std::vector<double> cdf(kEqualiseBins + 1, 0.0);
  const float scale = top > 0 ? kEqualiseBins / top : 0.f;
  for (std::size_t l = 0; l < gx.size(); ++l)
    for (std::size_t i = 0; i < gx[l]->size(); ++i)
      cdf[std::size_t(std::min(kEqualiseBins - 1, int(std::hypot((*gx[l])[i], (*gy[l])[i]) * scale))) + 1] += 1;
  std::vector<float> out(kEqualiseBins + 1, 0.f);
  double acc = 0;
  for (int b = 0; b <= kEqualiseBins; ++b) acc += cdf[std::size_t(b)], out[std::size_t(b)] = float(acc / std::max(1.0, total));
  *top_out = top;
  return out;
}

const Transducer& DefaultTransducer() {
  static const Transducer t = BuildTransducer();
  return t;
}

Result Map(const RadianceImage& in, Image<Float3>& out, const Options& o) {
  o.Check();
  const int w = in.width(), h = in.height();
  if (out.width() != w || out.height() != h) out = Image<Float3>(w, h);
  Result res;
  const std::size_t n = in.size();
  if (n == 0) return res;
  std::vector<std::uint8_t> valid(n);
  float y_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    valid[i] = !NoData(in[i]);
    if (valid[i]) y_max = std::max(y_max, Luminance(in[i]));
  }
  if (!(y_max > 0)) {
    for (std::size_t i = 0; i < n; ++i) out[i] = {0, 0, 0};
    return res;
  }
  const float clip = 1e-7f * y_max;
  std::vector<Level> lv = MakePyramid(w, h);
  std::vector<float> log_lum(n);
  double mean = 0;
  long n_valid = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (valid[i]) {
      log_lum[i] = std::log10(std::max(Luminance(in[i]), clip));
      mean += log_lum[i], ++n_valid;
    }
  mean /= double(n_valid);
  for (std::size_t i = 0; i < n; ++i)
    if (!valid[i]) log_lum[i] = float(mean);  // no data: a neutral surround, no contrast

  if (lv.empty()) {
    // Too small for a pyramid (under 3 pixels a side): no contrast processing.
    for (std::size_t i = 0; i < n; ++i) out[i] = valid[i] ? Float3{0.5f, 0.5f, 0.5f} : Float3{0, 0, 0};
    return res;
  }
  // Target gradients: response, compression, back.
  lv[0].value = log_lum;
  DownsampleChain(lv);
  const Transducer& tr = DefaultTransducer();
  const Transducer* trp = &tr;
  const float detail = float(o.detail), factor = float(o.contrast);
  for (Level& l : lv) {
    ImageView<const float> v = l.C(l.value);
    ImageView<float> gx = l.V(l.gx), gy = l.V(l.gy);
    par::ForEachPixel(par::Host{}, l.w, l.h, [=](int x, int y) {
      gx(x, y) = ToResponse(*trp, GradX(v, x, y) * detail);
      gy(x, y) = ToResponse(*trp, GradY(v, x, y) * detail);
    });
  }
  if (!o.equalise) {
    for (Level& l : lv)
      for (std::size_t i = 0; i < l.gx.size(); ++i) l.gx[i] *= factor, l.gy[i] *= factor;
  } else {
    // Equalisation: each response magnitude goes to the fraction of all (levels, pixels)
    // below it, times the factor -- the histogram of contrasts made flat.
    std::vector<const std::vector<float>*> gxs, gys;
    for (const Level& l : lv) gxs.push_back(&l.gx), gys.push_back(&l.gy);
    float top = 0;
    const std::vector<float> cdf = EqualisationCdf(gxs, gys, &top);
    const float* c = cdf.data();
    for (Level& l : lv)
      for (std::size_t i = 0; i < l.gx.size(); ++i) {
        const float s = EqualiseScale(l.gx[i], l.gy[i], c, kEqualiseBins, top, factor);
        l.gx[i] *= s, l.gy[i] *= s;
      }
  }
  for (Level& l : lv) {
    ImageView<float> gx = l.V(l.gx), gy = l.V(l.gy), wx = l.V(l.wx), wy = l.V(l.wy);
    par::ForEachPixel(par::Host{}, l.w, l.h, [=](int x, int y) {
      const float tx = ToContrast(*trp, gx(x, y)) / detail, ty = ToContrast(*trp, gy(x, y)) / detail;
      wx(x, y) = FitWeight(tx), wy(x, y) = FitWeight(ty);
      gx(x, y) = wx(x, y) * tx, gy(x, y) = wy(x, y) * ty;
    });
  }
  DivergenceSum(lv, true);
  const std::vector<float> b = lv[0].sum;

  // Conjugate gradients on A x = b, A x = the weighted divergence sum of x's gradients
  // (symmetric, negative semi-definite), from the input's log luminance.
  auto apply = [&](const std::vector<float>& x, std::vector<float>& ax) {
    lv[0].value = x;
    DownsampleChain(lv);
    DivergenceSum(lv, false);
    ax = lv[0].sum;
  };
  std::vector<float> x = log_lum, r(n), p(n), ap(n), best = x;
  apply(x, ap);
  for (std::size_t i = 0; i < n; ++i) r[i] = b[i] - ap[i];
  p = r;
  const double bb = std::max(Dot(b, b), 1e-30);
  double rr = Dot(r, r), best_rr = rr;
  const double tol2 = o.tolerance * o.tolerance;
  int it = 0;
  for (; it < o.iterations && rr / bb > tol2; ++it) {
    apply(p, ap);
    const double pap = Dot(p, ap);
    if (pap == 0) break;
    const float alpha = float(rr / pap);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < long(n); ++i) {
      x[std::size_t(i)] += alpha * p[std::size_t(i)];
      r[std::size_t(i)] -= alpha * ap[std::size_t(i)];
    }
    const double rr_new = Dot(r, r);
    if (rr_new < best_rr) best_rr = rr_new, best = x;
    const float beta = float(rr_new / rr);
    rr = rr_new;
#pragma omp parallel for schedule(static)
    for (long i = 0; i < long(n); ++i) p[std::size_t(i)] = r[std::size_t(i)] + beta * p[std::size_t(i)];
  }
  if (best_rr < rr) x = best, rr = best_rr;
  res.iterations = it;
  res.residual = std::sqrt(rr / bb);
  res.converged = rr / bb <= tol2;

  // Display: the 0.1 % to 99.9 % range of the result spans the display's 2.3 log10 units.
  float l_lo = 0, l_hi = 0;
  Quantiles(x, valid, 0.001, 0.999, &l_lo, &l_hi);
  float span = 0;
  DisplaySpan(l_lo, l_hi, &l_lo, &span);
  const float sat = float(o.saturation);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(n); ++i) {
    const std::size_t k = std::size_t(i);
    out[k] = valid[k] ? DisplayPixel(in[k], x[k], l_lo, span, clip, sat) : Float3{0, 0, 0};
  }
  return res;
}

}  // namespace hdrf::tonemap::m06
