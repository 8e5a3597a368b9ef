// Recorded RGB-D sequences in the TUM layout plus HDR extras (docs/formats.md).
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "common/image.h"
#include "common/se3.h"
#include "radiometry/sensor.h"

namespace hdrf::io {

// One associated colour/depth frame and what the sequence knows about it.
struct FrameInfo {
  double timestamp = 0;                   // colour timestamp, seconds
  std::filesystem::path color_path;       // absolute
  std::filesystem::path depth_path;       // absolute; empty when the frame has no depth
  std::optional<double> exposure_ms;      // from exposure.txt
  std::optional<double> gain;             // from exposure.txt
  std::optional<Pose> T_world_camera;     // from groundtruth.txt
  std::filesystem::path hdr_path;         // absolute; empty when hdr/<stem>.exr is absent
};

struct Frame {
  FrameInfo info;
  ColorImage color;
  DepthImage depth_m;  // metres; 0 = no data; empty when the frame has no depth
};

struct SequenceReadOptions {
  // Colour frames without a depth frame within 0.02 s are kept (with no depth) rather than
  // dropped; exposure sweeps use this, since depth is optional there.
  bool allow_missing_depth = false;
};

// Opens and checks a sequence folder: lists, sensor.json, exposure.txt, groundtruth.txt.
// Image files are checked when read. Every error names the file (and line).
class SequenceReader {
 public:
  explicit SequenceReader(const std::filesystem::path& folder, SequenceReadOptions options = {});

  const std::filesystem::path& folder() const { return folder_; }
  const SensorInfo& sensor() const { return sensor_; }
  const std::vector<FrameInfo>& frames() const { return frames_; }
  std::size_t size() const { return frames_.size(); }
  bool has_exposure() const { return has_exposure_; }
  bool has_groundtruth() const { return has_groundtruth_; }
  bool has_hdr() const { return has_hdr_; }
  // Colour frames left out because no depth frame lay within 0.02 s.
  std::size_t unmatched_color_frames() const { return unmatched_color_; }

  // Reads frame i's images; checks their size against sensor.json.
  Frame ReadFrame(std::size_t i) const;
  // Ground-truth radiance of frame i (hdr/<stem>.exr); throws if the sequence has none.
  RadianceImage ReadHdr(std::size_t i) const;

 private:
  std::filesystem::path folder_;
  SensorInfo sensor_;
  std::vector<FrameInfo> frames_;
  bool has_exposure_ = false;
  bool has_groundtruth_ = false;
  bool has_hdr_ = false;
  std::size_t unmatched_color_ = 0;
};

// The file stem of a frame at a timestamp (rgb/<stem>.png, depth/<stem>.png): "%.6f" seconds.
std::string TimestampName(double t);

// Writes a sequence frame by frame. Lists are appended and flushed after each frame, so a
// sequence cut short (crash, full disk) is still a valid, shorter sequence.
class SequenceWriter {
 public:
  struct Options {
    bool write_exposure = true;
    bool write_groundtruth = true;
    bool write_hdr = false;
    bool write_depth = true;  // false: no depth.txt nor depth/ (a sweep)
  };
  // Creates the folder (it must be empty or absent) and writes sensor.json.
  SequenceWriter(const std::filesystem::path& folder, const SensorInfo& sensor, Options options);
  SequenceWriter(const std::filesystem::path& folder, const SensorInfo& sensor)
      : SequenceWriter(folder, sensor, Options{}) {}
  // Reopens a sequence this writer made, to go on after an interruption: keeps its first
  // `keep_frames` colour frames (and the list lines of their timestamps and before), drops
  // the rest from the lists (their images stay, unlisted), and appends after them.
  static SequenceWriter Reopen(const std::filesystem::path& folder, Options options, std::size_t keep_frames);

  // depth may be null (a sweep without depth); gt and hdr may be absent / null.
  void Add(double timestamp, const ColorImage& color, const DepthRawImage* depth,
           std::optional<double> exposure_ms, const std::optional<Pose>& T_world_camera,
           const RadianceImage* hdr, std::optional<double> gain = std::nullopt);
  std::size_t size() const { return count_; }

 private:
  SequenceWriter(const std::filesystem::path& folder, const SensorInfo& sensor, Options options, bool);
  void Append(std::ofstream& out, const std::string& line, const char* name);
  std::filesystem::path folder_;
  SensorInfo sensor_;
  Options options_;
  std::ofstream rgb_, depth_, exposure_, gt_;
  double last_timestamp_ = 0;
  std::size_t count_ = 0;
};

}  // namespace hdrf::io
