#include "io/sequence.h"

#include <algorithm>

#include <cstdio>

#include "common/message.h"
#include "common/error.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/sensor_json.h"
#include "io/output_file.h"
#include "io/text_table.h"
#include "io/tum.h"

namespace hdrf::io {

namespace fs = std::filesystem;

namespace {

template <typename T>
std::vector<double> TimestampsOf(const std::vector<T>& v) {
  std::vector<double> t;
  for (const auto& e : v) t.push_back(e.timestamp);
  return t;
}

}  // namespace

std::string TimestampName(double t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", t);
  return buf;
}

SequenceReader::SequenceReader(const fs::path& folder, SequenceReadOptions options)
    : folder_(folder) {
  if (!fs::is_directory(folder))
    throw InputError(folder, fs::exists(folder) ? "is not a folder" : "sequence folder is missing");
  sensor_ = ReadSensorJson(folder / "sensor.json");
  const auto rgb = ReadImageList(folder / "rgb.txt");
  std::vector<ListEntry> depth;
  const bool has_depth_list = fs::exists(folder / "depth.txt");
  if (has_depth_list || !options.allow_missing_depth) depth = ReadImageList(folder / "depth.txt");

  std::vector<std::optional<std::size_t>> depth_of(rgb.size());
  for (auto [i, j] : AssociateTimestamps(TimestampsOf(rgb), TimestampsOf(depth))) depth_of[i] = j;

  std::vector<ExposureEntry> exposures;
  if (fs::exists(folder / "exposure.txt")) {
    exposures = ReadExposures(folder / "exposure.txt");
    has_exposure_ = true;
  }
  std::vector<TimedPose> gt;
  if (fs::exists(folder / "groundtruth.txt")) {
    gt = ReadTrajectory(folder / "groundtruth.txt");
    has_groundtruth_ = !gt.empty();
  }
  const auto exposure_t = TimestampsOf(exposures);
  const auto gt_t = TimestampsOf(gt);

  std::size_t hdr_count = 0;
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    if (!depth_of[i] && !options.allow_missing_depth) {
      ++unmatched_color_;
      continue;
    }
    FrameInfo f;
    f.timestamp = rgb[i].timestamp;
    f.color_path = folder / rgb[i].path;
    if (depth_of[i]) f.depth_path = folder / depth[*depth_of[i]].path;
    if (auto k = NearestTimestamp(exposure_t, f.timestamp)) {
      f.exposure_ms = exposures[*k].exposure_ms;
      f.gain = exposures[*k].gain;
    }
    if (auto k = NearestTimestamp(gt_t, f.timestamp)) f.T_world_camera = gt[*k].T_world_camera;
    const fs::path hdr = folder / "hdr" / (fs::path(rgb[i].path).stem().string() + ".exr");
    if (fs::exists(hdr)) {
      f.hdr_path = hdr;
      ++hdr_count;
    }
    frames_.push_back(std::move(f));
  }
  if (frames_.empty())
    throw InputError(folder / "rgb.txt",
                     "no colour frame has a depth frame within 0.02 s in depth.txt");
  // An exposure list none of whose stamps matches a frame is another recording's (or its
  // clock is offset): taking every frame as of unknown exposure would hide that.
  if (!exposures.empty() &&
      std::none_of(frames_.begin(), frames_.end(), [](const FrameInfo& f) { return f.exposure_ms.has_value(); })) {
    const auto [lo, hi] = std::minmax_element(exposure_t.begin(), exposure_t.end());
    throw InputError(folder / "exposure.txt",
                     "none of its " + std::to_string(exposures.size()) + " timestamps (" + Num(*lo, 6) +
                         " to " + Num(*hi, 6) + ") is within 0.02 s of a colour frame in rgb.txt (" +
                         Num(frames_.front().timestamp, 6) + " to " + Num(frames_.back().timestamp, 6) +
                         "): is it this recording's? (remove it to treat every exposure as unknown)");
  }
  has_hdr_ = hdr_count == frames_.size();
}

Frame SequenceReader::ReadFrame(std::size_t i) const {
  if (i >= frames_.size())
    throw Error("frame " + std::to_string(i) + " requested from a sequence of " +
                std::to_string(frames_.size()) + " frames (" + folder_.string() + ")");
  Frame f;
  f.info = frames_[i];
  const PinholeCamera& cam = sensor_.camera;
  // The size is checked from the header, before a frame is decoded.
  f.color = ReadColorImage(f.info.color_path, ExpectSize(f.info.color_path, cam.width, cam.height));
  if (!f.info.depth_path.empty()) {
    const DepthRawImage raw = ReadDepthImage(f.info.depth_path, ExpectSize(f.info.depth_path, cam.width, cam.height));
    f.depth_m = DepthToMetres(raw, sensor_.depth_scale);
  }
  return f;
}

RadianceImage SequenceReader::ReadHdr(std::size_t i) const {
  if (i >= frames_.size() || frames_[i].hdr_path.empty())
    throw InputError(folder_ / "hdr", "no ground-truth radiance for frame " + std::to_string(i));
  RadianceImage img = ReadExr(frames_[i].hdr_path);
  if (img.width() != sensor_.camera.width || img.height() != sensor_.camera.height)
    throw InputError(frames_[i].hdr_path, "size does not match sensor.json");
  return img;
}

namespace {
// The lists' headers, as written and as rewritten by Reopen.
constexpr const char* kRgbHeader = "# colour images\n# timestamp filename\n";
constexpr const char* kDepthHeader = "# depth images\n# timestamp filename\n";
constexpr const char* kExposureHeader = "# timestamp exposure_ms [analog_gain]\n";
constexpr const char* kGroundTruthHeader = "# timestamp tx ty tz qx qy qz qw (camera-to-world, metres)\n";
}  // namespace

SequenceWriter::SequenceWriter(const fs::path& folder, const SensorInfo& sensor, Options options)
    : folder_(folder), sensor_(sensor), options_(options) {
  if (fs::exists(folder) && !(fs::is_directory(folder) && fs::is_empty(folder)))
    throw InputError(folder, "output folder exists and is not empty; choose a new folder");
  std::error_code ec;
  fs::create_directories(folder / "rgb", ec);
  if (options.write_depth && !ec) fs::create_directories(folder / "depth", ec);
  if (options.write_hdr) fs::create_directories(folder / "hdr", ec);
  if (ec) throw InputError(folder, "cannot create folder: " + ec.message());
  WriteSensorJson(folder / "sensor.json", sensor);
  auto open = [&](std::ofstream& s, const char* name, const char* header) {
    s.open(folder / name);
    if (!s) throw InputError(folder / name, "cannot be opened for writing");
    s << header;
  };
  open(rgb_, "rgb.txt", kRgbHeader);
  if (options.write_depth) open(depth_, "depth.txt", kDepthHeader);
  if (options.write_exposure) open(exposure_, "exposure.txt", kExposureHeader);
  if (options.write_groundtruth) open(gt_, "groundtruth.txt", kGroundTruthHeader);
}

SequenceWriter::SequenceWriter(const fs::path& folder, const SensorInfo& sensor, Options options, bool)
    : folder_(folder), sensor_(sensor), options_(options) {}

SequenceWriter SequenceWriter::Reopen(const fs::path& folder, Options options, std::size_t keep_frames) {
  SequenceWriter w(folder, ReadSensorJson(folder / "sensor.json"), options, true);
  // The timestamp of the last colour frame kept; every list is cut after it.
  const fs::path rgb = folder / "rgb.txt";
  const std::vector<TextRow> frames = ReadTextTable(rgb);
  if (frames.size() < keep_frames)
    throw InputError(rgb, "lists " + std::to_string(frames.size()) + " frames, fewer than the " +
                              std::to_string(keep_frames) + " recorded as complete");
  const double last = keep_frames > 0 ? ParseNumber(rgb, frames[keep_frames - 1], 0, "timestamp") : -1;
  auto cut = [&](std::ofstream& s, const char* name, const char* header) {
    const fs::path file = folder / name;
    std::string content = header;
    for (const TextRow& row : ReadTextTable(file)) {
      if (keep_frames == 0 || ParseNumber(file, row, 0, "timestamp") > last) continue;
      for (std::size_t f = 0; f < row.fields.size(); ++f) content += (f ? " " : "") + row.fields[f];
      content += "\n";
    }
    WriteFileAtomically(file, content);
    s.open(file, std::ios::app);
    if (!s) throw InputError(file, "cannot be opened for writing");
  };
  cut(w.rgb_, "rgb.txt", kRgbHeader);
  if (options.write_depth) cut(w.depth_, "depth.txt", kDepthHeader);
  if (options.write_exposure) cut(w.exposure_, "exposure.txt", kExposureHeader);
  if (options.write_groundtruth) cut(w.gt_, "groundtruth.txt", kGroundTruthHeader);
  w.count_ = keep_frames;
  w.last_timestamp_ = last;
  return w;
}

void SequenceWriter::Append(std::ofstream& out, const std::string& line, const char* name) {
  out << line;
  out.flush();
  if (!out) throw InputError(folder_ / name, "write failed (disk full?)");
}

void SequenceWriter::Add(double timestamp, const ColorImage& color, const DepthRawImage* depth,
                         std::optional<double> exposure_ms,
                         const std::optional<Pose>& T_world_camera, const RadianceImage* hdr,
                         std::optional<double> gain) {
  if (count_ > 0 && !(timestamp > last_timestamp_))
    throw Error("sequence writer: timestamps must increase (" + TimestampName(timestamp) +
                " after " + TimestampName(last_timestamp_) + ")");
  if (color.width() != sensor_.camera.width || color.height() != sensor_.camera.height)
    throw Error("sequence writer: colour frame size differs from sensor.json");
  const std::string name = TimestampName(timestamp);
  // Images first, lists after: a list never names an image that was not written.
  WriteColorPng(folder_ / "rgb" / (name + ".png"), color);
  if (depth && !options_.write_depth) throw Error("sequence writer: depth given to a writer without depth");
  if (depth) WriteDepthPng(folder_ / "depth" / (name + ".png"), *depth);
  if (hdr && options_.write_hdr) WriteExr(folder_ / "hdr" / (name + ".exr"), *hdr);
  Append(rgb_, name + " rgb/" + name + ".png\n", "rgb.txt");
  if (depth) Append(depth_, name + " depth/" + name + ".png\n", "depth.txt");
  if (exposure_ms && options_.write_exposure) {
    char buf[96];
    if (gain)
      std::snprintf(buf, sizeof buf, "%s %.17g %.17g\n", name.c_str(), *exposure_ms, *gain);
    else
      std::snprintf(buf, sizeof buf, "%s %.17g\n", name.c_str(), *exposure_ms);
    Append(exposure_, buf, "exposure.txt");
  }
  if (T_world_camera && options_.write_groundtruth)
    Append(gt_, FormatTrajectoryLine({timestamp, *T_world_camera}), "groundtruth.txt");
  last_timestamp_ = timestamp;
  ++count_;
}

}  // namespace hdrf::io
