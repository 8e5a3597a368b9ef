#include "eval/calibration_accuracy.h"

#include <cmath>

#include "common/error.h"
#include "io/text_table.h"
#include "sim/synthetic_source.h"

namespace hdrf::eval {

std::vector<std::vector<double>> LoadDorfInverseCurves(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw InputError(file, "file is missing");
  std::vector<std::vector<double>> rows;
  for (const io::TextRow& r : io::ReadTextTable(file)) {
    if (r.fields.size() != 1024)
      throw InputError(file, r.line, "has " + std::to_string(r.fields.size()) + " values, expected 1024");
    std::vector<double> row(1024);
    for (std::size_t j = 0; j < 1024; ++j) row[j] = io::ParseNumber(file, r, j, "irradiance");
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw InputError(file, "holds no curves");
  return rows;
}

radiometry::InverseResponse LoadPcalibResponse(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw InputError(file, "file is missing");
  std::vector<double> v;
  for (const io::TextRow& r : io::ReadTextTable(file))
    for (std::size_t f = 0; f < r.fields.size(); ++f) v.push_back(io::ParseNumber(file, r, f, "response value"));
  if (v.size() != 256) throw InputError(file, "has " + std::to_string(v.size()) + " values, expected 256");
  return InverseFromCurves({&v, &v, &v});
}

radiometry::InverseResponse InverseFromCurves(const std::array<const std::vector<double>*, 3>& curves) {
  radiometry::InverseResponse r;
  for (int c = 0; c < 3; ++c) {
    const auto& row = *curves[std::size_t(c)];
    const int n = int(row.size());
    for (int i = 0; i < 256; ++i) {
      const double x = i * (n - 1) / 255.0;
      const int j = std::min(n - 2, int(x));
      r.table[c][i] = float(row[std::size_t(j)] + (row[std::size_t(j + 1)] - row[std::size_t(j)]) * (x - j) +
                            1e-4 * i / 255.0);
    }
  }
  radiometry::ScaleToUnitAt128(r);
  return r;
}

ResponseAccuracy CompareResponse(const radiometry::InverseResponse& est,
                                 const radiometry::InverseResponse& truth, int lo, int hi) {
  ResponseAccuracy a;
  for (int c = 0; c < 3; ++c) {
    const auto& t = truth.table[c];
    const auto& e = est.table[c];
    const double s = radiometry::ScaleOnto(est, truth, c, lo, hi);
    const double range = t[255] - t[0];
    for (int i = lo; i <= hi; ++i) {
      const double v = s * e[i];
      const double point = std::abs(v - t[i]) / range;
      const double band_lo = i > 0 ? 0.5 * (t[i - 1] + t[i]) : t[0];
      const double band_hi = i < 255 ? 0.5 * (t[i] + t[i + 1]) : t[255];
      const double bin = std::max({band_lo - v, v - band_hi, 0.0}) / range;
      if (point > a.point[c]) a.point[c] = point, a.point_level[c] = i;
      if (bin > a.bin[c]) a.bin[c] = bin, a.bin_level[c] = i;
      a.widest_bin[c] = std::max(a.widest_bin[c], (band_hi - band_lo) / range);
    }
  }
  return a;
}

radiometry::Sweep SimulateSweep(const radiometry::InverseResponse& truth,
                                const radiometry::NoiseModel& noise, int repeats, int width,
                                int height, const std::string& scene) {
  sim::SimOptions o;
  o.scene = scene;
  o.width = width;
  o.height = height;
  o.sweep = true;
  o.sweep_exposures_ms.clear();
  for (int k = 0; k <= 18; ++k) o.sweep_exposures_ms.push_back(0.25 * std::pow(2.0, k / 2.0));
  o.sweep_repeats = repeats;
  o.response = truth;
  o.noise = noise;
  sim::SyntheticSource src(o);
  radiometry::Sweep s;
  s.source = "simulated sweep";
  while (!src.done()) {
    sim::SimFrame f = src.Next();
    s.images.push_back(std::move(f.color));
    s.exposure_ms.push_back(f.exposure_ms);
  }
  return s;
}

}  // namespace hdrf::eval
