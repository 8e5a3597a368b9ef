#include "radiometry/calibration.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <sstream>

#include "common/error.h"
#include "radiometry/calibration_detail.h"

// The sweep checks, the response scale and monotonicity, and what every method shares.
// The methods live one per file: debevec.cpp, robertson.cpp, emor.cpp; the noise level
// function and the threshold refinement in thresholds.cpp; the HDR merge in merge.cpp.
namespace hdrf::radiometry {

namespace detail {

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

}  // namespace detail

using namespace detail;

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
  // Brightness must grow with exposure (the response is monotonic): a frame darker than a
  // shorter exposure means exposure.txt does not match the images (listed in reverse, or
  // shifted against rgb.txt). Judged on the mean green level of each exposure's frames (all
  // pixels: clipping only flattens the growth), with 2 levels of slack for noise.
  {
    std::vector<double> mean(g.exposure.size(), 0.0);
    const std::size_t n = s.images[0].size();
    for (std::size_t k = 0; k < g.exposure.size(); ++k) {
      double sum = 0;
      for (int i : g.images[k])
        for (std::size_t p = 0; p < n; p += 5) sum += s.images[std::size_t(i)][p].g;
      mean[k] = sum / (double(g.images[k].size()) * double((n + 4) / 5));
    }
    for (std::size_t k = 0; k + 1 < mean.size(); ++k)
      if (mean[k + 1] < mean[k] - 2.0) {
        std::ostringstream os;
        os.precision(4);
        os << s.source << ": frames get darker as the listed exposure grows (mean level " << mean[k] << " at "
           << g.exposure[k] << " ms, " << mean[k + 1] << " at " << g.exposure[k + 1]
           << " ms): the exposures in exposure.txt do not match the images (listed in reverse order, or shifted "
              "against rgb.txt?)";
        throw Error(os.str());
      }
  }
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
  // A camera or scene that moved: judged per pair of consecutive exposures, so one move in
  // a long sweep is not diluted.
  for (std::size_t k = 0; k + 1 < g.images.size(); ++k) {
    const OrderChange change = CompareBrightnessOrder(s.images[std::size_t(g.images[k][0])],
                                                      s.images[std::size_t(g.images[k + 1][0])], clip);
    if (change.moved()) {
      std::ostringstream os;
      os << s.source << ": the camera or the scene moved during the sweep (between "
         << g.exposure[k] << " and " << g.exposure[k + 1] << " ms, " << int(100.0 * change.share)
         << " % of image regions change brightness order); a sweep needs a static camera and a "
            "static scene";
      throw Error(os.str());
    }
  }
}

OrderChange CompareBrightnessOrder(const ColorImage& first, const ColorImage& second, ClipLevels clip) {
  // The brightness order of image regions is preserved between exposures (the response is
  // monotonic). Judged on means of 4 x 4 pixel blocks: near black a steep response turns
  // sensor noise into many levels (DoRF 159: +-10 levels), and single pixels then swap
  // order with no motion at all.
  constexpr int kBlock = 4;
  if (first.width() != second.width() || first.height() != second.height())
    throw Error("frames of different sizes cannot be compared");
  const int bw = first.width() / kBlock, bh = first.height() / kBlock;
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
  OrderChange result;
  if (bw * bh < 16) return result;
  const auto a = block_means(first), b = block_means(second);
  std::mt19937 rng(99);
  std::uniform_int_distribution<std::size_t> pick(0, std::size_t(bw) * std::size_t(bh) - 1);
  long violations = 0;
  for (int t = 0; t < 20000; ++t) {
    const std::size_t p = pick(rng), q = pick(rng);
    for (std::size_t c = 0; c < 3; ++c) {
      const float ap = a[p][c], aq = a[q][c], bp = b[p][c], bq = b[q][c];
      if (std::isnan(ap) || std::isnan(aq) || std::isnan(bp) || std::isnan(bq)) continue;
      if (std::abs(ap - aq) <= kMargin || std::abs(bp - bq) <= kMargin) continue;
      ++result.considered;
      violations += (ap > aq) != (bp > bq);
    }
  }
  if (result.considered > 0) result.share = double(violations) / double(result.considered);
  return result;
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

}  // namespace hdrf::radiometry
