// Grossberg & Nayar's empirical model of response (EMoR): the basis file and the fit of a
// sweep's curve onto it.
#include "radiometry/calibration.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>

#include "common/error.h"
#include "common/input_file.h"
#include "radiometry/calibration_detail.h"

namespace hdrf::radiometry {

using namespace detail;

namespace {
constexpr std::uintmax_t kMaxBasisBytes = 4 * kMiB;
}  // namespace

EmorBasis EmorBasis::Load(const std::filesystem::path& file) {
  // Read through the input-file checks: a FIFO or /dev/zero named as the basis is refused,
  // not waited on or read without end (the distribution's invemor.txt is 440 KB).
  std::istringstream in(ReadInputFile(file, kMaxBasisBytes, "an EMoR basis file (invemor.txt)"));
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
    while (ss >> v) {
      if (!std::isfinite(v)) throw InputError(file, line_no, "a value is not a finite number");
      blocks.back().push_back(v);
    }
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

}  // namespace hdrf::radiometry
