#include "pipeline/relocaliser.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <omp.h>

#include "common/error.h"

namespace hdrf::pipeline {

void RelocOptions::Check() const {
  if (candidates < 1 || candidates > 32) throw SettingError("reloc.candidates", "must be 1 to 32");
  if (!(min_translation_m > 0 && min_translation_m < 100)) throw SettingError("reloc.min_translation_m", "must be in (0, 100)");
  if (!(min_rotation_deg > 0 && min_rotation_deg <= 180)) throw SettingError("reloc.min_rotation_deg", "must be in (0, 180]");
  if (max_entries < 2 || max_entries > 1000000) throw SettingError("reloc.max_entries", "must be 2 to 1000000");
}

namespace {
constexpr int kCodeWidth = 40;
}

RelocCode MakeRelocCode(const ColorImage& color, const DepthImage& depth_m, const radiometry::InverseResponse& inv) {
  RelocCode c;
  const int W = color.width(), H = color.height();
  if (W <= 0 || H <= 0 || depth_m.width() != W || depth_m.height() != H) return c;
  c.width = std::min(kCodeWidth, W);
  c.height = std::max(1, int(std::lround(double(c.width) * H / W)));
  const std::size_t n = std::size_t(c.width) * std::size_t(c.height);
  c.depth.assign(n, 0.f);
  c.shade.assign(n, 0.f);
  c.lit.assign(n, 0);
  std::vector<double> zsum(n, 0), lsum(n, 0);
  std::vector<int> zn(n, 0), ln(n, 0), total(n, 0);
  // The cell of each column and row, once.
  std::vector<int> col(static_cast<std::size_t>(W)), row(static_cast<std::size_t>(H));
  for (int x = 0; x < W; ++x) col[std::size_t(x)] = std::min(c.width - 1, x * c.width / W);
  for (int y = 0; y < H; ++y) row[std::size_t(y)] = std::min(c.height - 1, y * c.height / H);
  // The code's rows on the threads: each owns its cells and adds its pixels in the order one
  // thread would (rows, then columns), so the sums are the same bits for any thread count.
  // At most kCodeThreads: on a 16-core machine scanning on the GPU, all of the cores took
  // 3.7 ms a keyframe on average and up to 7.6 (the frame's other threads busy beside them),
  // four 2.0 and at most 2.7 (H100 machine, 640x480).
  constexpr int kCodeThreads = 4;
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::min(kCodeThreads, omp_get_max_threads()))
  for (int cy = 0; cy < c.height; ++cy)
    for (int y = 0; y < H; ++y) {
      if (row[std::size_t(y)] != cy) continue;
      const std::size_t base = std::size_t(cy) * std::size_t(c.width);
      for (int x = 0; x < W; ++x) {
        const std::size_t k = base + std::size_t(col[std::size_t(x)]);
        ++total[k];
        const float z = depth_m(x, y);
        if (z > 0 && std::isfinite(z)) zsum[k] += z, ++zn[k];
        const Rgb8 p = color(x, y);
        const int lo = std::min({p.r, p.g, p.b}), hi = std::max({p.r, p.g, p.b});
        if (lo < 8 || hi > 247) continue;  // dark or clipped: its radiance is not known
        const double L = double(inv.table[0][p.r]) + inv.table[1][p.g] + inv.table[2][p.b];
        if (L > 0) lsum[k] += std::log(L), ++ln[k];
      }
    }
  double mean = 0;
  int lit = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (2 * zn[k] >= total[k] && zn[k] > 0) c.depth[k] = float(zsum[k] / zn[k]);
    if (2 * ln[k] >= total[k] && ln[k] > 0) {
      c.shade[k] = float(lsum[k] / ln[k]);
      c.lit[k] = 1;
      mean += c.shade[k];
      ++lit;
    }
  }
  if (lit > 0) {
    mean /= lit;
    for (std::size_t k = 0; k < n; ++k)
      if (c.lit[k]) c.shade[k] -= float(mean);
  }
  return c;
}

double RelocDistance(const RelocCode& a, const RelocCode& b) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (a.empty() || a.width != b.width || a.height != b.height) return kInf;
  double dz = 0, ds = 0;
  long nz = 0, ns = 0;
  for (std::size_t k = 0; k < a.depth.size(); ++k) {
    if (a.depth[k] > 0 && b.depth[k] > 0) dz += std::min(1.0, std::fabs(double(a.depth[k] - b.depth[k])) / 0.1), ++nz;
    if (a.lit[k] && b.lit[k]) ds += std::min(1.0, std::fabs(double(a.shade[k] - b.shade[k]))), ++ns;
  }
  if (5 * nz < long(a.depth.size())) return kInf;
  return dz / double(nz) + (ns > 0 ? ds / double(ns) : 1.0);
}

ColorImage Thumbnail(const ColorImage& color, int width) {
  const int W = color.width(), H = color.height();
  if (W <= 0 || H <= 0) return {};
  const int w = std::min(width, W), h = std::max(1, int(std::lround(double(w) * H / W)));
  ColorImage t(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t(x, y) = color(x * W / w, y * H / h);
  return t;
}

Relocaliser::Relocaliser(const RelocOptions& o) : o_((o.Check(), o)) {}

bool Relocaliser::Near(const Pose& entry, const Pose& T) const {
  const double deg = 3.14159265358979 / 180.0;
  // The relative pose's translation is as long as the gap between the two positions: an
  // entry that far away is not near, whatever the turn (the pose product only for the rest).
  if ((T.translation() - entry.translation()).norm() >= o_.min_translation_m * (1 + 1e-9)) return false;
  const Pose d = entry.inverse() * T;
  return se3::TranslationNorm(d) < o_.min_translation_m && se3::RotationAngle(d) < o_.min_rotation_deg * deg;
}

bool Relocaliser::Wants(const Pose& T) const {
  for (const RelocEntry& e : entries_)
    if (Near(e.T_world_camera, T)) return false;
  return true;
}

void Relocaliser::Add(RelocEntry e) {
  entries_.push_back(std::move(e));
  if (int(entries_.size()) > o_.max_entries) {
    std::vector<RelocEntry> kept;
    for (std::size_t i = 0; i < entries_.size(); i += 2) kept.push_back(std::move(entries_[i]));
    entries_ = std::move(kept);
  }
}

std::vector<const RelocEntry*> Relocaliser::Candidates(const RelocCode& code) const {
  std::vector<std::pair<double, const RelocEntry*>> d;
  for (const RelocEntry& e : entries_) {
    const double v = RelocDistance(code, e.code);
    if (std::isfinite(v)) d.emplace_back(v, &e);
  }
  const std::size_t k = std::min(d.size(), std::size_t(o_.candidates));
  std::partial_sort(d.begin(), d.begin() + long(k), d.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first || (a.first == b.first && a.second->frame < b.second->frame); });
  std::vector<const RelocEntry*> out;
  for (std::size_t i = 0; i < k; ++i) out.push_back(d[i].second);
  return out;
}

}  // namespace hdrf::pipeline
