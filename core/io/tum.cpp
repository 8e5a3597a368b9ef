#include "io/tum.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "io/output_file.h"
#include "io/text_table.h"

namespace hdrf::io {

namespace {

constexpr double kMaxPositionM = 1e9;

void CheckIncreasing(const std::filesystem::path& file, const TextRow& row, double previous,
                     double t, bool first) {
  if (!first && !(t > previous)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "timestamps must increase strictly: %.6f follows %.6f", t, previous);
    throw InputError(file, row.line, buf);
  }
}

void CheckFieldCount(const std::filesystem::path& file, const TextRow& row, std::size_t min,
                     std::size_t max, const char* layout) {
  if (row.fields.size() < min)
    throw InputError(file, row.line,
                     "line is truncated: expected \"" + std::string(layout) + "\", found " +
                         std::to_string(row.fields.size()) + " field(s)");
  if (row.fields.size() > max)
    throw InputError(file, row.line,
                     "too many fields: expected \"" + std::string(layout) + "\", found " +
                         std::to_string(row.fields.size()));
}

}  // namespace

std::vector<ListEntry> ReadImageList(const std::filesystem::path& file) {
  std::vector<ListEntry> out;
  for (const TextRow& row : ReadTextTable(file)) {
    CheckFieldCount(file, row, 2, 2, "timestamp path");
    const double t = ParseNumber(file, row, 0, "timestamp");
    CheckIncreasing(file, row, out.empty() ? 0 : out.back().timestamp, t, out.empty());
    // Images lie inside the sequence folder: a list cannot send the reader elsewhere.
    const std::filesystem::path image(row.fields[1]);
    bool up = false;
    for (const auto& part : image) up = up || part == "..";
    if (image.is_absolute() || up)
      throw InputError(file, row.line, "image path '" + row.fields[1] +
                                           "' leaves the sequence folder (paths are relative to it, without '..')");
    out.push_back({t, row.fields[1], row.line});
  }
  if (out.empty()) throw InputError(file, "lists no frames");
  return out;
}

std::vector<TimedPose> ReadTrajectory(const std::filesystem::path& file) {
  std::vector<TimedPose> out;
  for (const TextRow& row : ReadTextTable(file)) {
    CheckFieldCount(file, row, 8, 8, "timestamp tx ty tz qx qy qz qw");
    double v[8];
    static const char* names[8] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
    for (int i = 0; i < 8; ++i) v[i] = ParseNumber(file, row, i, names[i]);
    // A position beyond a million kilometres is no camera's (1e300 made every error infinite,
    // and `eval` reported an ATE of inf).
    for (int i = 1; i <= 3; ++i)
      if (!(std::fabs(v[i]) <= kMaxPositionM))
        throw InputError(file, row.line, std::string(names[i]) + " is " + row.fields[std::size_t(i)] +
                                             ": a camera position is at most 1e9 m from the origin");
    CheckIncreasing(file, row, out.empty() ? 0 : out.back().timestamp, v[0], out.empty());
    try {
      out.push_back({v[0], se3::FromTranslationQuaternion(Vec3(v[1], v[2], v[3]), v[4], v[5],
                                                          v[6], v[7])});
    } catch (const Error& e) {
      throw InputError(file, row.line, e.what());
    }
  }
  return out;
}

std::vector<ExposureEntry> ReadExposures(const std::filesystem::path& file) {
  std::vector<ExposureEntry> out;
  for (const TextRow& row : ReadTextTable(file)) {
    CheckFieldCount(file, row, 2, 3, "timestamp exposure_ms [analog_gain]");
    ExposureEntry e;
    e.timestamp = ParseNumber(file, row, 0, "timestamp");
    e.exposure_ms = ParseNumber(file, row, 1, "exposure_ms");
    if (!(e.exposure_ms > 0))
      throw InputError(file, row.line, "exposure_ms must be positive, got " + row.fields[1]);
    if (row.fields.size() == 3) {
      e.gain = ParseNumber(file, row, 2, "analog_gain");
      if (!(*e.gain > 0))
        throw InputError(file, row.line, "analog_gain must be positive, got " + row.fields[2]);
    }
    CheckIncreasing(file, row, out.empty() ? 0 : out.back().timestamp, e.timestamp, out.empty());
    out.push_back(e);
  }
  return out;
}

std::string FormatTrajectoryLine(const TimedPose& p) {
  const Eigen::Quaterniond q(p.T_world_camera.rotation());
  const Vec3 t = p.T_world_camera.translation();
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.6f %.7f %.7f %.7f %.9f %.9f %.9f %.9f\n", p.timestamp, t.x(),
                t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  return buf;
}

void WriteTrajectory(const std::filesystem::path& file, const std::vector<TimedPose>& poses) {
  std::string s = "# timestamp tx ty tz qx qy qz qw (camera-to-world, metres)\n";
  for (const auto& p : poses) s += FormatTrajectoryLine(p);
  WriteFileAtomically(file, s);
}

std::vector<std::pair<std::size_t, std::size_t>> AssociateTimestamps(
    const std::vector<double>& a, const std::vector<double>& b, double max_dt) {
  struct Candidate {
    double dt;
    std::size_t i, j;
  };
  std::vector<Candidate> cand;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // b is sorted: only entries within max_dt can match.
    auto lo = std::lower_bound(b.begin(), b.end(), a[i] - max_dt);
    for (auto it = lo; it != b.end() && *it <= a[i] + max_dt; ++it)
      cand.push_back({std::abs(*it - a[i]), i, std::size_t(it - b.begin())});
  }
  std::stable_sort(cand.begin(), cand.end(),
                   [](const Candidate& x, const Candidate& y) { return x.dt < y.dt; });
  std::vector<char> used_a(a.size(), 0), used_b(b.size(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const auto& c : cand) {
    if (used_a[c.i] || used_b[c.j]) continue;
    used_a[c.i] = used_b[c.j] = 1;
    out.emplace_back(c.i, c.j);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::optional<std::size_t> NearestTimestamp(const std::vector<double>& sorted, double t,
                                            double max_dt) {
  if (sorted.empty()) return std::nullopt;
  auto it = std::lower_bound(sorted.begin(), sorted.end(), t);
  std::optional<std::size_t> best;
  double best_dt = max_dt;
  for (auto c : {it, it == sorted.begin() ? it : it - 1}) {
    if (c == sorted.end()) continue;
    const double dt = std::abs(*c - t);
    if (dt <= best_dt) {
      best_dt = dt;
      best = std::size_t(c - sorted.begin());
    }
  }
  return best;
}

}  // namespace hdrf::io
