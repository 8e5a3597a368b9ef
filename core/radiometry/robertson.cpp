// Robertson, Borman & Stevenson (2003): the response by alternating the per-pixel radiance
// (E-step) and the per-level average (M-step).
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

}  // namespace hdrf::radiometry
