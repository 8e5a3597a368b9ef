#include "response_curves.h"

#include <algorithm>

#include "common/error.h"
#include "io/text_table.h"
#include "radiometry/calibration.h"

namespace hdrf::experiments {

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

}  // namespace hdrf::experiments
