// Relocalisation: a database of small codes of the frames a scan fused, looked up when the
// camera is lost. A code is the frame shrunk to about 40x30 cells: each cell's mean depth,
// and its mean log radiance less the frame's mean log radiance. An exposure change scales
// radiance, which shifts log radiance by one constant for the whole frame, so the codes of
// one view at two exposures agree. Candidates are the entries whose codes are nearest; the
// pipeline then tracks the frame from each candidate's pose against the model and keeps a
// pose only when it verifies.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "radiometry/response.h"

namespace hdrf::pipeline {

struct RelocOptions {
  bool enabled = true;
  int candidates = 3;               // entries tracked from when the camera is lost
  double min_translation_m = 0.10;  // a new entry after this much motion...
  double min_rotation_deg = 10;     // ...or this much turning since the nearest entry
  int max_entries = 2000;           // beyond it, every other entry is dropped
  void Check() const;               // throws SettingError naming the option
};

struct RelocCode {
  int width = 0, height = 0;
  std::vector<float> depth;        // metres; 0 = too few pixels with depth in the cell
  std::vector<float> shade;        // log radiance less the frame's mean (valid where lit[i])
  std::vector<std::uint8_t> lit;   // 1 where the cell's colour was neither dark nor saturated
  bool empty() const { return depth.empty(); }
};

struct RelocEntry {
  int frame = 0;
  Pose T_world_camera = Pose::Identity();
  RelocCode code;
  ColorImage thumbnail;  // the frame's colour, small: what the studio shows the operator

  RelocEntry() = default;
  RelocEntry(int f, const Pose& T, RelocCode c, ColorImage t)
      : frame(f), T_world_camera(T), code(std::move(c)), thumbnail(std::move(t)) {}
  RelocEntry(const RelocEntry& o) : frame(o.frame), T_world_camera(o.T_world_camera), code(o.code), thumbnail(o.thumbnail.Clone()) {}
  RelocEntry& operator=(const RelocEntry& o) {
    if (this != &o) *this = RelocEntry(o);
    return *this;
  }
  RelocEntry(RelocEntry&&) = default;
  RelocEntry& operator=(RelocEntry&&) = default;
};

// The code of a frame (colour through the inverse response, depth in metres).
RelocCode MakeRelocCode(const ColorImage& color, const DepthImage& depth_m,
                        const radiometry::InverseResponse& inverse);
// Distance between two codes: mean depth difference (in units of 10 cm, capped at 1) plus
// mean shade difference (capped at 1) over cells both have; infinite where they share
// fewer than a fifth of their cells.
double RelocDistance(const RelocCode& a, const RelocCode& b);
ColorImage Thumbnail(const ColorImage& color, int width = 80);

class Relocaliser {
 public:
  explicit Relocaliser(const RelocOptions& o = {});
  // Whether a frame fused at this pose is far enough from every entry to be added.
  bool Wants(const Pose& T_world_camera) const;
  // Whether an entry at `entry` is near enough to a frame at `T` to leave it out.
  bool Near(const Pose& entry, const Pose& T) const;
  // Whether adding one more entry drops every other one (options().max_entries).
  bool Full() const { return int(entries_.size()) + 1 > o_.max_entries; }
  void Add(RelocEntry e);
  // The nearest entries to a code, best first (at most options().candidates).
  std::vector<const RelocEntry*> Candidates(const RelocCode& code) const;
  const std::vector<RelocEntry>& entries() const { return entries_; }
  void Restore(std::vector<RelocEntry> entries) { entries_ = std::move(entries); }
  const RelocOptions& options() const { return o_; }

 private:
  RelocOptions o_;
  std::vector<RelocEntry> entries_;
};

}  // namespace hdrf::pipeline
