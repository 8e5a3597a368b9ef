// TUM RGB-D text files: image lists, trajectories, exposures (docs/formats.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/se3.h"

namespace hdrf::io {

struct ListEntry {
  double timestamp = 0;
  std::string path;  // relative to the sequence folder, as written in the list
  int line = 0;
};

struct TimedPose {
  double timestamp = 0;
  Pose T_world_camera = Pose::Identity();
};

struct ExposureEntry {
  double timestamp = 0;
  double exposure_ms = 0;
  std::optional<double> gain;
};

// Each reader checks every line (count and parse of fields, finite numbers, strictly
// increasing timestamps) and throws InputError naming the file and line.
std::vector<ListEntry> ReadImageList(const std::filesystem::path& file);
std::vector<TimedPose> ReadTrajectory(const std::filesystem::path& file);
std::vector<ExposureEntry> ReadExposures(const std::filesystem::path& file);

// Writers produce exactly what the readers accept ("%.6f" timestamps).
std::string FormatTrajectoryLine(const TimedPose& p);
void WriteTrajectory(const std::filesystem::path& file, const std::vector<TimedPose>& poses);

// Pairs (index into a, index into b) whose timestamps differ by at most max_dt, chosen as
// the TUM tools do: closest pairs first, each entry used once, result sorted by a.
std::vector<std::pair<std::size_t, std::size_t>> AssociateTimestamps(
    const std::vector<double>& a, const std::vector<double>& b, double max_dt = 0.02);

// Index of the entry of `sorted` nearest to t within max_dt, if any.
std::optional<std::size_t> NearestTimestamp(const std::vector<double>& sorted, double t,
                                            double max_dt = 0.02);

}  // namespace hdrf::io
