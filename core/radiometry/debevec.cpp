// Debevec & Malik (1997): the response from a least-squares fit of ln f^-1 with a smoothness
// prior, over sampled pixels of the sweep.
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

}  // namespace hdrf::radiometry
