// The HDR merge of a sweep through a response and noise model, and its consistency across
// exposures.
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
                                                  const RadianceImage& merged, ClipLevels clip,
                                                  const NoiseModel* noise) {
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
        if (noise) {  // only samples the noise leaves within 5 %: the rest measure the noise
          const double R = inv.table[c][z], ss = noise->sigma_s[c], sc = noise->sigma_c[c];
          if (!(R > 0) || R * ss * ss + sc * sc > 0.0025 * R * R) continue;
        }
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
